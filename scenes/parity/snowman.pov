// POV-Ray 3.7 scene written by `prism export pov` from snowman.toml; regenerate, do not edit.
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

background { rgb <0.6, 0.75, 0.95> }

camera {
  perspective
  location <0.0, 0.0, -1.0>
  direction <0.0, 0.0, 1.0>
  up <0.0, 1.9999999999999998, -0.0>
  right <1.0, -0.0, -0.0> * 1.9999999999999998 * image_width / image_height
}

light_source { <-3.0, 5.0, -2.0>, color rgb <1.0, 1.0, 1.0>
}

// "ground" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.85, 0.88, 0.95, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "body" sphere
sphere { <0.0, 0.0, -0.0>, 0.8
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.25, 3.0>
  texture {
    pigment { rgbft <0.95, 0.95, 0.98, 0.0, 0.0> }
    finish {
      ambient rgb <0.15, 0.15, 0.15> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.2 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "chest" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 0.8, 3.0>
  texture {
    pigment { rgbft <0.95, 0.95, 0.98, 0.0, 0.0> }
    finish {
      ambient rgb <0.15, 0.15, 0.15> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.2 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "head" sphere
sphere { <0.0, 0.0, -0.0>, 0.4
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 1.65, 3.0>
  texture {
    pigment { rgbft <0.95, 0.95, 0.98, 0.0, 0.0> }
    finish {
      ambient rgb <0.15, 0.15, 0.15> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.2 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "left_eye" sphere
sphere { <0.0, 0.0, -0.0>, 0.06
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.14, 1.75, 2.64>
  texture {
    pigment { rgbft <0.03, 0.03, 0.03, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "right_eye" sphere
sphere { <0.0, 0.0, -0.0>, 0.06
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.14, 1.75, 2.64>
  texture {
    pigment { rgbft <0.03, 0.03, 0.03, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "nose" cone
cone { <0.0, -0.02, -0.3>, 0.07, <0.0, -0.25, -0.85>, 0.0
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 1.65, 3.0>
  texture {
    pigment { rgbft <1.0, 0.45, 0.05, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 30.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "button_top" sphere
sphere { <0.0, 0.0, -0.0>, 0.06
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 1.0, 2.434314575050762>
  texture {
    pigment { rgbft <0.03, 0.03, 0.03, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "button_middle" sphere
sphere { <0.0, 0.0, -0.0>, 0.06
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 0.8, 2.4>
  texture {
    pigment { rgbft <0.03, 0.03, 0.03, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "button_bottom" sphere
sphere { <0.0, 0.0, -0.0>, 0.06
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 0.6000000000000001, 2.434314575050762>
  texture {
    pigment { rgbft <0.03, 0.03, 0.03, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

