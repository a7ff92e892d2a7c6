// POV-Ray 3.7 scene written by `prism export pov` from image_map_repeat.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.35, 0.4, 0.5> }

camera {
  perspective
  location <0.0, 1.3, -3.6>
  direction <0.0, -0.2297926837559573, 0.9732396017899367>
  up <0.0, 0.8062580849999643, 0.19036649229165825>
  right <1.0, -0.0, -0.0> * 0.8284271247461901 * image_width / image_height
}

light_source { <-3.0, 5.0, -4.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <4.0, 2.0, -3.0>, color rgb <0.3, 0.3, 0.3>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -0.1
  texture {
    pigment {
      checker color rgbft <0.9, 0.88, 0.8, 0.0, 0.0>, color rgbft <0.25, 0.3, 0.4, 0.0, 0.0>
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.4, 0.0, 0.0, -0.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "repeated" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <0.8693332436601615, 0.0, 0.23293714059226867, 0.0, 0.9, -0.0, -0.23293714059226867, -0.0, 0.8693332436601615, -2.0, 0.1, -0.0>
  texture {
    pigment {
      image_map { png "image_map.png" map_type 0 repeat <3.0, 2.0> offset <0.25, 0.1> }
      matrix <0.8693332436601615, 0.0, 0.23293714059226867, 0.0, 0.9, -0.0, -0.23293714059226867, -0.0, 0.8693332436601615, -2.0, 0.1, -0.0>
    }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "once" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <0.9, 0.0, -0.0, 0.0, 0.9, -0.0, -0.0, -0.0, 0.9, -1.0, 0.1, 0.2>
  texture {
    pigment {
      image_map { png "image_map_rgb16.png" map_type 0 interpolate 2 once repeat <1.5, 0.75> offset <-0.2, 0.3> }
      matrix <0.9, 0.0, -0.0, 0.0, 0.9, -0.0, -0.0, -0.0, 0.9, -1.0, 0.1, 0.2>
    }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "torus" torus
torus { 1.0, 0.4
  matrix <0.45, 0.0, -0.0, 0.0, 0.3686184199300463, 0.25810939635797076, -0.0, -0.25810939635797076, 0.3686184199300463, 0.35, 0.45, -0.2>
  texture {
    pigment {
      image_map { png "image_map.png" map_type 5 interpolate 3 repeat <2.0, 1.0> }
      matrix <0.45, 0.0, -0.0, 0.0, 0.3686184199300463, 0.25810939635797076, -0.0, -0.25810939635797076, 0.3686184199300463, 0.35, 0.45, -0.2>
    }
    finish {
      ambient rgb <0.2, 0.2, 0.2> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "bumped" sphere
sphere { <1.55, 0.4, -0.3>, 0.45
  texture {
    pigment { rgbft <0.8, 0.7, 0.5, 0.0, 0.0> }
    normal {
      bump_map { png "image_map.png" map_type 1 interpolate 2 repeat <2.0, 1.0> offset <0.1, 0.0> bump_size 1.5 }
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.5 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

