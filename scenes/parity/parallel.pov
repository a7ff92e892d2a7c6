// POV-Ray 3.7 scene written by `prism export pov` from parallel.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <0.7, 0.75, 0.9>
}

background { rgb <0.5, 0.65, 0.9> }

camera {
  perspective
  location <0.0, 1.5, -1.5>
  direction <0.0, -0.3265202527980472, 0.9451902054680313>
  up <0.0, 0.9840697549417842, 0.33995136988898>
  right <1.0, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <4.0, 6.0, -2.0>, color rgb <0.8, 0.8, 0.7>
  parallel point_at <0.0, 0.0, 4.0>
}

light_source { <-3.0, 1.0, 2.0>, color rgb <0.3, 0.2, 0.4>
  shadowless
}

light_source { <0.0, 0.5, 3.0>, color rgb <0.6, 0.6, 0.5>
  fade_distance 2.0 fade_power 1.0
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.75, 0.75, 0.7, 0.0, 0.0> }
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

// "ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.55
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.0, -0.45, 4.0>
  texture {
    pigment { rgbft <0.9, 0.4, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.6 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "ghost" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.4, -0.55, 4.3>
  texture {
    pigment { rgbft <0.3, 0.8, 0.4, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.5 roughness 0.03
      metallic 0.0
    }
  }
  interior { ior 1.0 }
  no_shadow
}

// "column" cylinder
cylinder { <1.5, -1.0, 5.0>, <1.5, 0.8, 5.0>, 0.25
  texture {
    pigment { rgbft <0.4, 0.5, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 20.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

