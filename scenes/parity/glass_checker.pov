// POV-Ray 3.7 scene written by `prism export pov` from glass_checker.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 8
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.55, 0.65, 0.85> }

camera {
  perspective
  location <0.0, 1.3, -1.0>
  direction <0.0, -0.3552177606235726, 0.9347835805883489>
  up <0.0, 0.8717934846917947, 0.331281524182882>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <2.0, 4.0, -0.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.3, 0.3, 0.3, 0.0, 0.0> }
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

// "glass_ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.75
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.2, -0.05, 4.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.8 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "red_ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.6, -0.35, 5.2>
  texture {
    pigment { rgbft <0.8, 0.15, 0.1, 0.0, 0.0> }
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

// box
box { <-3.98, -1.0, 7.98>, <-3.02, -0.8, 7.02>
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
box { <-2.98, -1.0, 7.98>, <-2.02, -0.8, 7.02>
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
box { <-1.98, -1.0, 7.98>, <-1.02, -0.8, 7.02>
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
box { <-0.98, -1.0, 7.98>, <-0.02, -0.8, 7.02>
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
box { <0.02, -1.0, 7.98>, <0.98, -0.8, 7.02>
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
box { <1.02, -1.0, 7.98>, <1.98, -0.8, 7.02>
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
box { <2.02, -1.0, 7.98>, <2.98, -0.8, 7.02>
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
box { <3.02, -1.0, 7.98>, <3.98, -0.8, 7.02>
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
box { <-3.98, -1.0, 6.98>, <-3.02, -0.8, 6.02>
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
box { <-2.98, -1.0, 6.98>, <-2.02, -0.8, 6.02>
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
box { <-1.98, -1.0, 6.98>, <-1.02, -0.8, 6.02>
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
box { <-0.98, -1.0, 6.98>, <-0.02, -0.8, 6.02>
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
box { <0.02, -1.0, 6.98>, <0.98, -0.8, 6.02>
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
box { <1.02, -1.0, 6.98>, <1.98, -0.8, 6.02>
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
box { <2.02, -1.0, 6.98>, <2.98, -0.8, 6.02>
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
box { <3.02, -1.0, 6.98>, <3.98, -0.8, 6.02>
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
box { <-3.98, -1.0, 5.98>, <-3.02, -0.8, 5.02>
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
box { <-2.98, -1.0, 5.98>, <-2.02, -0.8, 5.02>
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
box { <-1.98, -1.0, 5.98>, <-1.02, -0.8, 5.02>
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
box { <-0.98, -1.0, 5.98>, <-0.02, -0.8, 5.02>
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
box { <0.02, -1.0, 5.98>, <0.98, -0.8, 5.02>
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
box { <1.02, -1.0, 5.98>, <1.98, -0.8, 5.02>
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
box { <2.02, -1.0, 5.98>, <2.98, -0.8, 5.02>
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
box { <3.02, -1.0, 5.98>, <3.98, -0.8, 5.02>
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
box { <-3.98, -1.0, 4.98>, <-3.02, -0.8, 4.02>
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
box { <-2.98, -1.0, 4.98>, <-2.02, -0.8, 4.02>
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
box { <-1.98, -1.0, 4.98>, <-1.02, -0.8, 4.02>
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
box { <-0.98, -1.0, 4.98>, <-0.02, -0.8, 4.02>
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
box { <0.02, -1.0, 4.98>, <0.98, -0.8, 4.02>
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
box { <1.02, -1.0, 4.98>, <1.98, -0.8, 4.02>
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
box { <2.02, -1.0, 4.98>, <2.98, -0.8, 4.02>
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
box { <3.02, -1.0, 4.98>, <3.98, -0.8, 4.02>
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
box { <-3.98, -1.0, 3.98>, <-3.02, -0.8, 3.02>
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
box { <-2.98, -1.0, 3.98>, <-2.02, -0.8, 3.02>
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
box { <-1.98, -1.0, 3.98>, <-1.02, -0.8, 3.02>
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
box { <-0.98, -1.0, 3.98>, <-0.02, -0.8, 3.02>
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
box { <0.02, -1.0, 3.98>, <0.98, -0.8, 3.02>
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
box { <1.02, -1.0, 3.98>, <1.98, -0.8, 3.02>
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
box { <2.02, -1.0, 3.98>, <2.98, -0.8, 3.02>
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
box { <3.02, -1.0, 3.98>, <3.98, -0.8, 3.02>
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
box { <-3.98, -1.0, 2.98>, <-3.02, -0.8, 2.02>
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
box { <-2.98, -1.0, 2.98>, <-2.02, -0.8, 2.02>
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
box { <-1.98, -1.0, 2.98>, <-1.02, -0.8, 2.02>
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
box { <-0.98, -1.0, 2.98>, <-0.02, -0.8, 2.02>
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
box { <0.02, -1.0, 2.98>, <0.98, -0.8, 2.02>
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
box { <1.02, -1.0, 2.98>, <1.98, -0.8, 2.02>
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
box { <2.02, -1.0, 2.98>, <2.98, -0.8, 2.02>
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
box { <3.02, -1.0, 2.98>, <3.98, -0.8, 2.02>
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

