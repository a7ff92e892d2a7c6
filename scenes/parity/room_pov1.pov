// POV-Ray 3.7 scene written by `prism export pov` from room_pov1.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 +A0.3 +AM1 +R3 -J
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.0, 0.0, 0.0> }

camera {
  perspective
  location <0.0, 0.0, -1.0>
  direction <0.0, 0.0, 1.0>
  up <0.0, 1.9999999999999998, -0.0>
  right <1.0, -0.0, -0.0> * 1.9999999999999998 * image_width / image_height
}

light_source { <0.0, 2.5, 3.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
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

// "ceiling" plane
plane { <0.0, -1.0, -0.0>, -3.0
  texture {
    pigment { rgbft <0.9, 0.9, 0.9, 0.0, 0.0> }
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

// "left_wall" plane
plane { <1.0, 0.0, -0.0>, -4.0
  texture {
    pigment { rgbft <0.75, 0.25, 0.25, 0.0, 0.0> }
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

// "right_wall" plane
plane { <-1.0, 0.0, -0.0>, -4.0
  texture {
    pigment { rgbft <0.25, 0.75, 0.25, 0.0, 0.0> }
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

// "back_wall" plane
plane { <0.0, 0.0, -1.0>, -8.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
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

// "front_wall" plane
plane { <0.0, 0.0, 1.0>, -2.0
  texture {
    pigment { rgbft <0.3, 0.3, 0.8, 0.0, 0.0> }
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

// "orange_sphere" sphere
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.2, -0.5, 3.5>
  texture {
    pigment { rgbft <0.9, 0.3, 0.1, 0.0, 0.0> }
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

// "mirror_sphere" sphere
sphere { <0.0, 0.0, -0.0>, 0.75
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, -0.25, 4.5>
  texture {
    pigment { rgbft <0.9, 0.9, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.02, 0.02, 0.02> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.1 brilliance 1.0
      phong 0.9 phong_size 120.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.8, 0.8, 0.8>, rgb <0.8, 0.8, 0.8> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "cone" cone
cone { <0.0, -0.2, 5.0>, 0.6, <0.0, 1.2, 6.0>, 0.0 open
  texture {
    pigment { rgbft <0.9, 0.8, 0.2, 0.0, 0.0> }
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

// "cone_base" disc
disc { <0.0, -0.2, 5.0>, <0.0, -0.813733471206735, -0.5812381937190965>, 0.6
  texture {
    pigment { rgbft <0.2, 0.3, 0.9, 0.0, 0.0> }
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

