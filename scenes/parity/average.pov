// POV-Ray 3.7 scene written by `prism export pov` from average.toml; regenerate, do not edit.
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
      average
      turbulence <0.3, 0.3, 0.3>
      pigment_map {
        [1.0 gradient <1.0, 0.0, -0.0>
          color_map {
            [0.0 color rgbft <0.9, 0.85, 0.7, 0.0, 0.0>]
            [1.0 color rgbft <0.3, 0.35, 0.5, 0.0, 0.0>]
          }]
        [2.0 bozo
          color_map {
            [0.0 color rgbft <0.8, 0.8, 0.8, 0.0, 0.0>]
            [1.0 color rgbft <0.5, 0.3, 0.2, 0.0, 0.0>]
          }
          matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>]
      }
      matrix <0.8, 0.0, -0.0, 0.0, 0.8, -0.0, -0.0, -0.0, 0.8, 0.0, 0.0, -0.0>
    }
    normal {
      average
      normal_map {
        [1.0 bumps 0.4
          matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>]
        [1.0 ripples 0.5
          frequency 2.0]
      }
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.3 roughness 0.02
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "wall" plane
plane { <0.0, 0.0, -1.0>, -9.0
  texture {
    pigment {
      average
      pigment_map {
        [1.0 checker color rgbft <0.8, 0.8, 0.9, 0.0, 0.0>, color rgbft <0.5, 0.55, 0.7, 0.0, 0.0>]
        [1.0 onion
          color_map {
            [0.0 color rgbft <0.9, 0.9, 0.7, 0.0, 0.0>]
            [1.0 color rgbft <0.6, 0.7, 0.9, 0.0, 0.0>]
          }]
      }
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

// "three_pigments" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
  texture {
    pigment {
      average
      pigment_map {
        [1.0 checker color rgbft <0.9, 0.3, 0.1, 0.0, 0.0>, color rgbft <0.1, 0.3, 0.9, 0.0, 0.0>
          matrix <0.25, 0.0, -0.0, 0.0, 0.25, -0.0, -0.0, -0.0, 0.25, 0.0, 0.0, -0.0>]
        [1.5 marble
          turbulence <0.8, 0.8, 0.8>
          color_map {
            [0.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
            [1.0 color rgbft <0.2, 0.2, 0.2, 0.0, 0.0>]
          }]
        [0.5 color rgbft <0.2, 0.9, 0.2, 0.0, 0.0>]
      }
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
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

// "three_normals" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
  texture {
    pigment { rgbft <0.3, 0.7, 0.4, 0.0, 0.0> }
    normal {
      average
      normal_map {
        [1.0 bumps 0.6
          matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
        [1.0 dents 1.0
          matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>]
        [2.0 granite bump_size 0.5
          slope_map {
            [0.0 <0.0, 0.0>]
            [0.5 <0.5, 2.0>]
            [1.0 <1.0, 0.0>]
          }]
      }
      matrix <0.8528685319524433, 0.1503837331804353, 0.49999999999999994, -0.17364817766693033, 0.984807753012208, -0.0, -0.49240387650610395, -0.08682408883346515, 0.8660254037844387, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.5 roughness 0.01
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "mirror" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
  texture {
    pigment { rgbft <0.6, 0.6, 0.7, 0.0, 0.0> }
    normal {
      average
      turbulence <0.3, 0.3, 0.3>
      normal_map {
        [1.0 wrinkles 0.6]
        [0.5 gradient <0.0, 1.0, -0.0>
          normal_map {
            [0.0 bumps 0.8
              matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>]
            [1.0 ripples 0.5]
          }
          frequency 3.0]
      }
      matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.8 phong_size 120.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.6, 0.6, 0.6>, rgb <0.6, 0.6, 0.6> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "see_through" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
  texture {
    pigment {
      average
      pigment_map {
        [1.0 color rgbft <1.0, 0.9, 0.3, 0.9, 0.0>]
        [1.0 leopard
          color_map {
            [0.0 color rgbft <0.1, 0.1, 0.6, 0.0, 0.0>]
            [1.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.8>]
          }
          matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
      }
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
    }
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

// "nested" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.3, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
  texture {
    pigment {
      gradient <0.0, 1.0, -0.0>
      pigment_map {
        [0.3 color rgbft <0.4, 0.5, 0.9, 0.0, 0.0>]
        [0.7 average
          pigment_map {
            [1.0 radial
              color_map {
                [0.0 color rgbft <0.9, 0.9, 0.2, 0.0, 0.0>]
                [1.0 color rgbft <0.9, 0.2, 0.2, 0.0, 0.0>]
              }
              frequency 4.0]
            [2.0 wood
              color_map {
                [0.0 color rgbft <0.3, 0.2, 0.1, 0.0, 0.0>]
                [1.0 color rgbft <0.9, 0.7, 0.4, 0.0, 0.0>]
              }]
          }
          matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>]
      }
      matrix <1.2, 0.0, -0.0, 0.0, 1.2, -0.0, -0.0, -0.0, 1.2, 0.0, 0.6, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.3, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
    }
    normal {
      bozo
      normal_map {
        [0.0 average
          normal_map {
            [1.0 bumps 0.5
              matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
            [1.0 waves 0.6
              frequency 4.0]
          }]
        [1.0 quilted 0.4
          matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>]
      }
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.4, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.3, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.4 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "box" box
box { <-0.5, -0.5, 0.5>, <0.5, 0.5, -0.5>
  matrix <0.8191520442889918, 0.0, 0.573576436351046, 0.19617469496901108, 0.9396926207859084, -0.2801664995932355, -0.5389855446957562, 0.3420201433256687, 0.7697511313200572, -1.2, 0.9, 6.0>
  texture {
    pigment {
      average
      pigment_map {
        [2.0 brick color rgbft <0.9, 0.9, 0.85, 0.0, 0.0>, color rgbft <0.7, 0.3, 0.2, 0.0, 0.0> brick_size <8.0, 3.0, 4.5> mortar 0.5
          matrix <0.05, 0.0, -0.0, 0.0, 0.05, -0.0, -0.0, -0.0, 0.05, 0.0, 0.0, -0.0>]
        [1.0 agate
          color_map {
            [0.0 color rgbft <0.9, 0.8, 0.5, 0.0, 0.0>]
            [1.0 color rgbft <0.3, 0.2, 0.1, 0.0, 0.0>]
          }]
      }
      matrix <0.9396926207859084, 0.3420201433256687, -0.0, -0.3420201433256687, 0.9396926207859084, -0.0, -0.0, -0.0, 1.0, 0.0, 0.0, -0.0>
      matrix <0.8191520442889918, 0.0, 0.573576436351046, 0.19617469496901108, 0.9396926207859084, -0.2801664995932355, -0.5389855446957562, 0.3420201433256687, 0.7697511313200572, -1.2, 0.9, 6.0>
    }
    normal {
      average
      normal_map {
        [1.0 facets 0.5 size 0.3]
        [1.0 crackle bump_size 0.8
          matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>]
      }
      matrix <0.8191520442889918, 0.0, 0.573576436351046, 0.19617469496901108, 0.9396926207859084, -0.2801664995932355, -0.5389855446957562, 0.3420201433256687, 0.7697511313200572, -1.2, 0.9, 6.0>
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

