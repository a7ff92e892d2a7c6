// POV-Ray 3.7 scene written by `prism export pov` from assumed_gamma.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 +A0.3 +AM1 +R3 -J
#version 3.7;

global_settings {
  assumed_gamma 2.2
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <0.8, 0.8, 0.8>
}

background { rgb <0.35, 0.4, 0.5> }

camera {
  perspective
  location <0.0, 1.0, -3.4>
  direction <0.0, -0.131208719028083, 0.9913547659899606>
  up <0.0, 0.8212651783924951, 0.10869686184606553>
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
      reflection { rgb <0.15, 0.15, 0.15>, rgb <0.15, 0.15, 0.15> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "srgb" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <0.8693332436601615, 0.0, 0.23293714059226867, 0.0, 0.9, -0.0, -0.23293714059226867, -0.0, 0.8693332436601615, -1.95, 0.1, -0.0>
  texture {
    pigment {
      image_map { png "image_map.png" map_type 0 interpolate 2 }
      matrix <0.8693332436601615, 0.0, 0.23293714059226867, 0.0, 0.9, -0.0, -0.23293714059226867, -0.0, 0.8693332436601615, -1.95, 0.1, -0.0>
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

// "grey4" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <0.9, 0.0, -0.0, 0.0, 0.9, -0.0, -0.0, -0.0, 0.9, -0.95, 0.1, -0.0>
  texture {
    pigment {
      image_map { png "image_map_grey4.png" map_type 0 }
      matrix <0.9, 0.0, -0.0, 0.0, 0.9, -0.0, -0.0, -0.0, 0.9, -0.95, 0.1, -0.0>
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

// "matched" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <0.8693332436601615, 0.0, -0.23293714059226867, 0.0, 0.9, -0.0, 0.23293714059226867, -0.0, 0.8693332436601615, 1.05, 0.1, -0.0>
  texture {
    pigment {
      image_map { png "image_map_gamma.png" map_type 0 interpolate 3 }
      matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
      matrix <0.8693332436601615, 0.0, -0.23293714059226867, 0.0, 0.9, -0.0, 0.23293714059226867, -0.0, 0.8693332436601615, 1.05, 0.1, -0.0>
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

// "ball" sphere
sphere { <0.55, 0.35, -0.9>, 0.3
  texture {
    pigment { rgbft <0.8, 0.25, 0.1, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.8 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "glass" sphere
sphere { <-0.4, 0.3, -1.0>, 0.25
  texture {
    pigment { rgbft <0.9, 0.95, 1.0, 0.8, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.1 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.6 roughness 0.01
      metallic 0.0
      reflection { rgb <0.1, 0.1, 0.1>, rgb <0.1, 0.1, 0.1> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.5 }
}

