// POV-Ray 3.7 scene written by `prism export pov` from camera_inside.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 10
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.55, 0.65, 0.85> }

camera {
  perspective
  location <0.0, 0.2, -0.0>
  direction <0.0, -0.15799050110667287, 0.9874406319167053>
  up <0.0, 1.1401982292917678, 0.1824317166866829>
  right <1.0, -0.0, -0.0> * 1.1547005383792515 * image_width / image_height
}

light_source { <3.0, 6.0, -3.0>, color rgb <1.0, 1.0, 1.0>
}

// "water" sphere
sphere { <0.0, 0.0, -0.0>, 1.0
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.3, 0.6, 0.3>
  texture {
    pigment { rgbft <0.85, 0.95, 1.0, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.5 phong_size 120.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.33 }
}

// "pebble" sphere
sphere { <0.0, 0.0, -0.0>, 0.12
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.35, -0.15, 0.6>
  texture {
    pigment { rgbft <0.9, 0.8, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.2
  texture {
    pigment { rgbft <0.35, 0.33, 0.3, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "back_wall" plane
plane { <0.0, 0.0, -1.0>, -12.0
  texture {
    pigment { rgbft <0.7, 0.72, 0.75, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.6, 4.5>
  texture {
    pigment { rgbft <0.8, 0.2, 0.15, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.6 phong_size 60.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "post" cylinder
cylinder { <1.6, -1.2, 5.5>, <1.6, 1.5, 5.5>, 0.2
  texture {
    pigment { rgbft <0.2, 0.6, 0.3, 0.0, 0.0> }
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

// box
box { <-2.98, -1.2, 3.98>, <-2.02, -1.1, 3.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-2.98, -1.2, 4.98>, <-2.02, -1.1, 4.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <-2.98, -1.2, 5.98>, <-2.02, -1.1, 5.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-2.98, -1.2, 6.98>, <-2.02, -1.1, 6.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <-1.98, -1.2, 3.98>, <-1.02, -1.1, 3.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <-1.98, -1.2, 4.98>, <-1.02, -1.1, 4.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-1.98, -1.2, 5.98>, <-1.02, -1.1, 5.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <-1.98, -1.2, 6.98>, <-1.02, -1.1, 6.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-0.98, -1.2, 3.98>, <-0.02, -1.1, 3.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-0.98, -1.2, 4.98>, <-0.02, -1.1, 4.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <-0.98, -1.2, 5.98>, <-0.02, -1.1, 5.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <-0.98, -1.2, 6.98>, <-0.02, -1.1, 6.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <0.02, -1.2, 3.98>, <0.98, -1.1, 3.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <0.02, -1.2, 4.98>, <0.98, -1.1, 4.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <0.02, -1.2, 5.98>, <0.98, -1.1, 5.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <0.02, -1.2, 6.98>, <0.98, -1.1, 6.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <1.02, -1.2, 3.98>, <1.98, -1.1, 3.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <1.02, -1.2, 4.98>, <1.98, -1.1, 4.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <1.02, -1.2, 5.98>, <1.98, -1.1, 5.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <1.02, -1.2, 6.98>, <1.98, -1.1, 6.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <2.02, -1.2, 3.98>, <2.98, -1.1, 3.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <2.02, -1.2, 4.98>, <2.98, -1.1, 4.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

// box
box { <2.02, -1.2, 5.98>, <2.98, -1.1, 5.02>
  texture {
    pigment { rgbft <0.15, 0.2, 0.35, 0.0, 0.0> }
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

// box
box { <2.02, -1.2, 6.98>, <2.98, -1.1, 6.02>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
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

