// POV-Ray 3.7 scene written by `prism export pov` from focal_blur_adaptive.toml; regenerate, do not edit.
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

background { rgb <0.6, 0.7, 0.9> }

camera {
  perspective
  location <0.0, 0.8, -1.5>
  direction <0.0, -0.2131670752167256, 0.9770157614099921>
  up <0.0, 0.8093863580565894, 0.17659338721234683>
  right <1.0, -0.0, -0.0> * 0.8284271247461901 * image_width / image_height
  aperture 0.6
  blur_samples 7, 64
  focal_point <0.0, -0.40000000000000013, 3.999999999999999>
  variance 0.0001
  confidence 0.9
}

light_source { <-2.0, 4.0, -1.0>, color rgb <1.0, 1.0, 1.0>
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

// "near" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.9, -0.45, 2.0>
  texture {
    pigment { rgbft <0.9, 0.3, 0.1, 0.0, 0.0> }
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

// "focus" sphere
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.3, -0.3, 4.2>
  texture {
    pigment { rgbft <0.2, 0.7, 0.3, 0.0, 0.0> }
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

// "far" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.6, -0.2, 7.0>
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

// box
box { <-3.98, -1.0, 8.98>, <-3.02, -0.8, 8.02>
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
box { <-2.98, -1.0, 8.98>, <-2.02, -0.8, 8.02>
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
box { <-1.98, -1.0, 8.98>, <-1.02, -0.8, 8.02>
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
box { <-0.98, -1.0, 8.98>, <-0.02, -0.8, 8.02>
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
box { <0.02, -1.0, 8.98>, <0.98, -0.8, 8.02>
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
box { <1.02, -1.0, 8.98>, <1.98, -0.8, 8.02>
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
box { <2.02, -1.0, 8.98>, <2.98, -0.8, 8.02>
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
box { <3.02, -1.0, 8.98>, <3.98, -0.8, 8.02>
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
box { <-3.98, -1.0, 7.98>, <-3.02, -0.8, 7.02>
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
box { <-2.98, -1.0, 7.98>, <-2.02, -0.8, 7.02>
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
box { <-1.98, -1.0, 7.98>, <-1.02, -0.8, 7.02>
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
box { <-0.98, -1.0, 7.98>, <-0.02, -0.8, 7.02>
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
box { <0.02, -1.0, 7.98>, <0.98, -0.8, 7.02>
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
box { <1.02, -1.0, 7.98>, <1.98, -0.8, 7.02>
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
box { <2.02, -1.0, 7.98>, <2.98, -0.8, 7.02>
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
box { <3.02, -1.0, 7.98>, <3.98, -0.8, 7.02>
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
box { <-3.98, -1.0, 6.98>, <-3.02, -0.8, 6.02>
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
box { <-2.98, -1.0, 6.98>, <-2.02, -0.8, 6.02>
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
box { <-1.98, -1.0, 6.98>, <-1.02, -0.8, 6.02>
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
box { <-0.98, -1.0, 6.98>, <-0.02, -0.8, 6.02>
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
box { <0.02, -1.0, 6.98>, <0.98, -0.8, 6.02>
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
box { <1.02, -1.0, 6.98>, <1.98, -0.8, 6.02>
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
box { <2.02, -1.0, 6.98>, <2.98, -0.8, 6.02>
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
box { <3.02, -1.0, 6.98>, <3.98, -0.8, 6.02>
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
box { <-3.98, -1.0, 5.98>, <-3.02, -0.8, 5.02>
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
box { <-2.98, -1.0, 5.98>, <-2.02, -0.8, 5.02>
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
box { <-1.98, -1.0, 5.98>, <-1.02, -0.8, 5.02>
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
box { <-0.98, -1.0, 5.98>, <-0.02, -0.8, 5.02>
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
box { <0.02, -1.0, 5.98>, <0.98, -0.8, 5.02>
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
box { <1.02, -1.0, 5.98>, <1.98, -0.8, 5.02>
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
box { <2.02, -1.0, 5.98>, <2.98, -0.8, 5.02>
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
box { <3.02, -1.0, 5.98>, <3.98, -0.8, 5.02>
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
box { <-3.98, -1.0, 4.98>, <-3.02, -0.8, 4.02>
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
box { <-2.98, -1.0, 4.98>, <-2.02, -0.8, 4.02>
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
box { <-1.98, -1.0, 4.98>, <-1.02, -0.8, 4.02>
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
box { <-0.98, -1.0, 4.98>, <-0.02, -0.8, 4.02>
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
box { <0.02, -1.0, 4.98>, <0.98, -0.8, 4.02>
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
box { <1.02, -1.0, 4.98>, <1.98, -0.8, 4.02>
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
box { <2.02, -1.0, 4.98>, <2.98, -0.8, 4.02>
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
box { <3.02, -1.0, 4.98>, <3.98, -0.8, 4.02>
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
box { <-3.98, -1.0, 3.98>, <-3.02, -0.8, 3.02>
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
box { <-2.98, -1.0, 3.98>, <-2.02, -0.8, 3.02>
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
box { <-1.98, -1.0, 3.98>, <-1.02, -0.8, 3.02>
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
box { <-0.98, -1.0, 3.98>, <-0.02, -0.8, 3.02>
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
box { <0.02, -1.0, 3.98>, <0.98, -0.8, 3.02>
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
box { <1.02, -1.0, 3.98>, <1.98, -0.8, 3.02>
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
box { <2.02, -1.0, 3.98>, <2.98, -0.8, 3.02>
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
box { <3.02, -1.0, 3.98>, <3.98, -0.8, 3.02>
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
box { <-3.98, -1.0, 2.98>, <-3.02, -0.8, 2.02>
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
box { <-2.98, -1.0, 2.98>, <-2.02, -0.8, 2.02>
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
box { <-1.98, -1.0, 2.98>, <-1.02, -0.8, 2.02>
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
box { <-0.98, -1.0, 2.98>, <-0.02, -0.8, 2.02>
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
box { <0.02, -1.0, 2.98>, <0.98, -0.8, 2.02>
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
box { <1.02, -1.0, 2.98>, <1.98, -0.8, 2.02>
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
box { <2.02, -1.0, 2.98>, <2.98, -0.8, 2.02>
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
box { <3.02, -1.0, 2.98>, <3.98, -0.8, 2.02>
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

