// POV-Ray 3.7 scene written by `prism export pov` from mirrors.toml; regenerate, do not edit.
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

background { rgb <0.4, 0.5, 0.7> }

camera {
  perspective
  location <1.2, 0.4, -0.5>
  direction <-0.5899833436564258, -0.12756396619598395, 0.7972747887248998>
  up <-0.08761929234695251, 1.1452670340890516, 0.11840444911750339>
  right <0.8038418992031009, 0.0, 0.5948430054102947> * 1.1547005383792515 * image_width / image_height
}

light_source { <0.0, 3.0, 2.0>, color rgb <1.0, 1.0, 1.0>
}

// "left_mirror" plane
plane { <1.0, 0.0, -0.0>, -2.5
  texture {
    pigment { rgbft <0.9, 0.9, 0.95, 0.0, 0.0> }
    finish {
      ambient rgb <0.03, 0.03, 0.03> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.05 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.85, 0.85, 0.85>, rgb <0.85, 0.85, 0.85> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "right_mirror" plane
plane { <-1.0, 0.0, -0.0>, -2.5
  texture {
    pigment { rgbft <0.9, 0.9, 0.95, 0.0, 0.0> }
    finish {
      ambient rgb <0.03, 0.03, 0.03> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.05 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.85, 0.85, 0.85>, rgb <0.85, 0.85, 0.85> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.6, 0.55, 0.5, 0.0, 0.0> }
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

// "back" plane
plane { <0.0, 0.0, -1.0>, -12.0
  texture {
    pigment { rgbft <0.5, 0.6, 0.5, 0.0, 0.0> }
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

// "stripe" box
box { <-2.4, -1.0, 5.0>, <2.4, -0.95, 4.6>
  texture {
    pigment { rgbft <0.9, 0.9, 0.2, 0.0, 0.0> }
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

// "red" sphere
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.8, -0.5, 4.0>
  texture {
    pigment { rgbft <0.9, 0.2, 0.15, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.6 phong_size 50.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "blue" sphere
sphere { <0.0, 0.0, -0.0>, 0.4
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.0, -0.6, 6.0>
  texture {
    pigment { rgbft <0.2, 0.3, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.6 phong_size 50.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "chrome" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.4, -0.65, 3.0>
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
    finish {
      ambient rgb <0.02, 0.02, 0.02> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.1 brilliance 1.0
      phong 0.9 phong_size 120.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.7, 0.7, 0.7>, rgb <0.7, 0.7, 0.7> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

