// POV-Ray 3.7 scene written by `prism export pov` from patterns_noise.toml; regenerate, do not edit.
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
      checker color rgbft <0.9, 0.88, 0.8, 0.0, 0.0>, color rgbft <0.25, 0.3, 0.4, 0.0, 0.0>
      turbulence <0.3, 0.3, 0.3> omega 0.6 lambda 2.5 octaves 4
      matrix <0.75, 0.0, -0.0, 0.0, 0.75, -0.0, -0.0, -0.0, 0.75, 0.0, 0.0, -0.0>
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
      granite
      color_map {
        [0.0 color rgbft <0.9, 0.85, 0.8, 0.0, 0.0>]
        [0.4 color rgbft <0.55, 0.5, 0.5, 0.0, 0.0>]
        [1.0 color rgbft <0.1, 0.1, 0.15, 0.0, 0.0>]
      }
      matrix <3.0, 0.0, -0.0, 0.0, 3.0, -0.0, -0.0, -0.0, 3.0, 0.0, 0.0, -0.0>
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

// "bozo" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
  texture {
    pigment {
      bozo
      color_map {
        [0.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
        [0.4 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
        [0.6 color rgbft <0.2, 0.4, 0.9, 0.0, 0.0>]
        [1.0 color rgbft <0.1, 0.1, 0.5, 0.0, 0.0>]
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

// "spotted" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
  texture {
    pigment {
      spotted
      turbulence <0.5, 0.2, 0.8>
      color_map {
        [0.0 color rgbft <0.9, 0.3, 0.1, 0.0, 0.0>]
        [0.5 color rgbft <0.95, 0.9, 0.6, 0.0, 0.0>]
        [1.0 color rgbft <0.2, 0.1, 0.1, 0.0, 0.0>]
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

// "marble" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
  texture {
    pigment {
      marble
      turbulence <0.8, 0.8, 0.8>
      color_map {
        [0.0 color rgbft <0.95, 0.95, 0.95, 0.0, 0.0>]
        [0.7 color rgbft <0.85, 0.85, 0.9, 0.0, 0.0>]
        [1.0 color rgbft <0.2, 0.2, 0.35, 0.0, 0.0>]
      }
      matrix <0.383022221559489, 0.3213938048432696, -0.0, -0.3213938048432696, 0.383022221559489, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
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

// "wood" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
  texture {
    pigment {
      wood
      turbulence <0.05, 0.05, 0.05> octaves 3
      color_map {
        [0.0 color rgbft <0.85, 0.6, 0.3, 0.0, 0.0>]
        [0.9 color rgbft <0.6, 0.35, 0.15, 0.0, 0.0>]
        [1.0 color rgbft <0.4, 0.2, 0.08, 0.0, 0.0>]
      }
      matrix <0.1477211629518312, 0.0, 0.02604722665003955, 0.02565151074942515, 0.02604722665003956, -0.1454769465589431, -0.004523053441056872, 0.1477211629518312, 0.02565151074942516, 0.0, 0.0, -0.0>
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

// "agate" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.9, 0.9, 6.0>
  texture {
    pigment {
      agate
      color_map {
        [0.0 color rgbft <0.5, 0.1, 0.1, 0.0, 0.0>]
        [0.5 color rgbft <0.95, 0.8, 0.7, 0.0, 0.0>]
        [1.0 color rgbft <0.3, 0.05, 0.05, 0.0, 0.0>]
      }
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.4, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.9, 0.9, 6.0>
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

// "wrinkles" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.5, 0.9, 6.0>
  texture {
    pigment {
      wrinkles
      color_map {
        [0.0 color rgbft <0.1, 0.3, 0.1, 0.0, 0.0>]
        [0.6 color rgbft <0.8, 0.9, 0.5, 0.0, 0.0>]
        [1.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
      }
      matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.5, 0.9, 6.0>
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

// "turbulent_gradient" sphere
sphere { <0.0, 0.0, -0.0>, 0.7
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, 0.9, 6.0>
  texture {
    pigment {
      gradient <0.0, 1.0, -0.0>
      turbulence <0.6, 0.6, 0.6> omega 0.45 lambda 1.8 octaves 7
      color_map {
        [0.0 color rgbft <0.9, 0.2, 0.5, 0.0, 0.0>]
        [1.0 color rgbft <0.9, 0.9, 1.0, 0.0, 0.6>]
      }
      frequency 3.0
      sine_wave
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, 0.9, 6.0>
    }
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

