// POV-Ray 3.7 scene written by `prism export pov` from crackle.toml; regenerate, do not edit.
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

background { rgb <0.4, 0.45, 0.55> }

camera {
  perspective
  location <0.0, 1.1, 1.2>
  direction <0.0, -0.26311740579210885, 0.9647638212377321>
  up <0.0, 1.0044485138015167, 0.2739405037640501>
  right <1.0, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-3.0, 6.0, -1.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <4.0, 3.0, 1.0>, color rgb <0.4, 0.4, 0.4>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment {
      crackle solid
      color_map {
        [0.0 color rgbft <0.85, 0.8, 0.7, 0.0, 0.0>]
        [0.35 color rgbft <0.55, 0.5, 0.45, 0.0, 0.0>]
        [0.5 color rgbft <0.35, 0.4, 0.45, 0.0, 0.0>]
        [0.7 color rgbft <0.7, 0.55, 0.4, 0.0, 0.0>]
        [1.0 color rgbft <0.25, 0.2, 0.2, 0.0, 0.0>]
      }
      matrix <0.6, 0.0, -0.0, 0.0, 0.6, -0.0, -0.0, -0.0, 0.6, 0.0, 0.0, -0.0>
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

// "wall" plane
plane { <0.0, 0.0, -1.0>, -9.0
  texture {
    pigment {
      quilted control0 0.2 control1 0.9
      color_map {
        [0.0 color rgbft <0.9, 0.85, 0.75, 0.0, 0.0>]
        [0.15 color rgbft <0.6, 0.55, 0.6, 0.0, 0.0>]
        [0.3 color rgbft <0.3, 0.3, 0.45, 0.0, 0.0>]
      }
      matrix <0.8, 0.0, -0.0, 0.0, 0.8, -0.0, -0.0, -0.0, 0.8, 0.0, 0.0, -0.0>
    }
    normal {
      granite bump_size 0.4 accuracy 0.05
      matrix <2.0, 0.0, -0.0, 0.0, 2.0, -0.0, -0.0, -0.0, 2.0, 0.0, 0.0, -0.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "crackle_default" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
  texture {
    pigment {
      crackle
      color_map {
        [0.0 color rgbft <0.1, 0.1, 0.1, 0.0, 0.0>]
        [0.05 color rgbft <0.1, 0.1, 0.1, 0.0, 0.0>]
        [0.1 color rgbft <0.95, 0.9, 0.8, 0.0, 0.0>]
        [1.0 color rgbft <0.9, 0.6, 0.3, 0.0, 0.0>]
      }
      matrix <0.25, 0.0, -0.0, 0.0, 0.25, -0.0, -0.0, -0.0, 0.25, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
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

// "crackle_metric1" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
  texture {
    pigment {
      crackle
      form <1.0, 0.0, 0.0> metric 1.0
      color_map {
        [0.0 color rgbft <1.0, 1.0, 0.9, 0.0, 0.0>]
        [0.6 color rgbft <0.2, 0.5, 0.8, 0.0, 0.0>]
        [1.0 color rgbft <0.05, 0.1, 0.3, 0.0, 0.0>]
      }
      matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
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

// "crackle_metric3" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
  texture {
    pigment {
      crackle
      form <0.8, 0.4, 0.0> metric 3.0 offset 0.3
      color_map {
        [0.0 color rgbft <0.2, 0.6, 0.3, 0.0, 0.0>]
        [1.0 color rgbft <0.95, 0.95, 0.7, 0.0, 0.0>]
      }
      frequency 2.0
      sine_wave
      matrix <0.2819077862357725, 0.0, 0.10260604299770061, 0.0513030214988503, 0.2598076211353316, -0.14095389311788625, -0.08885943981780715, 0.14999999999999997, 0.24413930440481213, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
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

// "crackle_turbulent" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
  texture {
    pigment {
      crackle
      turbulence <0.4, 0.4, 0.4> omega 0.6 octaves 3
      color_map {
        [0.0 color rgbft <0.4, 0.05, 0.05, 0.0, 0.0>]
        [0.08 color rgbft <0.4, 0.05, 0.05, 0.0, 0.0>]
        [0.12 color rgbft <0.95, 0.85, 0.85, 0.0, 0.0>]
        [1.0 color rgbft <0.8, 0.5, 0.5, 0.0, 0.0>]
      }
      matrix <0.35, 0.0, -0.0, 0.0, 0.35, -0.0, -0.0, -0.0, 0.35, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
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

// "crackle_normal" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
  texture {
    pigment { rgbft <0.9, 0.4, 0.2, 0.0, 0.0> }
    normal {
      crackle bump_size 0.6
      matrix <0.25, 0.0, -0.0, 0.0, 0.25, -0.0, -0.0, -0.0, 0.25, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
    }
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

// "quilted_normal" box
box { <-0.5, -0.5, 0.5>, <0.5, 0.5, -0.5>
  matrix <0.8191520442889918, 0.0, 0.573576436351046, 0.19617469496901108, 0.9396926207859084, -0.2801664995932355, -0.5389855446957562, 0.3420201433256687, 0.7697511313200572, -1.9, 0.9, 6.0>
  texture {
    pigment { rgbft <0.9, 0.8, 0.5, 0.0, 0.0> }
    normal {
      quilted 0.8 control0 0.3 control1 0.8
      matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>
      matrix <0.8191520442889918, 0.0, 0.573576436351046, 0.19617469496901108, 0.9396926207859084, -0.2801664995932355, -0.5389855446957562, 0.3420201433256687, 0.7697511313200572, -1.9, 0.9, 6.0>
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

// "gradient_normal" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.6, 0.9, 6.0>
  texture {
    pigment { rgbft <0.4, 0.5, 0.9, 0.0, 0.0> }
    normal {
      gradient <1.0, 1.0, -0.0> bump_size -0.7
      frequency 3.0
      triangle_wave
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.6, 0.9, 6.0>
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

// "marble_normal" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.7, 0.9, 6.0>
  texture {
    pigment { rgbft <0.85, 0.85, 0.8, 0.0, 0.0> }
    normal {
      marble bump_size 0.5
      turbulence <0.6, 0.6, 0.6>
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.4, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.7, 0.9, 6.0>
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

// "crackle_metric_normal" sphere
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.9, 0.9, 6.5>
  texture {
    pigment { rgbft <0.3, 0.7, 0.4, 0.0, 0.0> }
    normal {
      crackle bump_size 1.2 accuracy 0.01
      form <0.0, 1.0, -0.5> metric 2.5
      turbulence <0.2, 0.2, 0.2>
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.9, 0.9, 6.5>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.8 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.2, 0.2, 0.2>, rgb <0.2, 0.2, 0.2> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "facets" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.9, 0.75, 6.0>
  texture {
    pigment { rgbft <0.8, 0.8, 0.9, 0.0, 0.0> }
    normal {
      facets 0.5 size 0.15
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.9, 0.75, 6.0>
    }
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

// "facets_coords" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.9, 0.75, 6.5>
  texture {
    pigment { rgbft <0.9, 0.7, 0.8, 0.0, 0.0> }
    normal {
      facets 0.5 coords 0.6 metric 3.0
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.9, 0.75, 6.5>
    }
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

