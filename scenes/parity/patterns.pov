// POV-Ray 3.7 scene written by `prism export pov` from patterns.toml; regenerate, do not edit.
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
      matrix <0.649519052838329, 0.0, 0.37499999999999994, 0.0, 0.75, -0.0, -0.37499999999999994, -0.0, 0.649519052838329, 0.0, 0.0, -0.0>
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
      brick color rgbft <0.8, 0.8, 0.75, 0.0, 0.0>, color rgbft <0.6, 0.2, 0.1, 0.0, 0.0> brick_size <8.0, 3.0, 4.5> mortar 0.6
      matrix <0.12, 0.0, -0.0, 0.0, 0.12, -0.0, -0.0, -0.0, 0.12, 0.05, 0.0, -0.0>
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

// "hexagons" box
box { <-0.8, -0.25, 0.8>, <0.8, 0.25, -0.8>
  matrix <0.9063077870366499, 0.0, 0.42261826174069944, 0.109381654946615, 0.9659258262890683, -0.23456971600980447, -0.40821789367673483, 0.25881904510252074, 0.875426098065593, 2.9, -0.7, 6.5>
  texture {
    pigment {
      hexagon color rgbft <0.9, 0.2, 0.2, 0.0, 0.0>, color rgbft <0.2, 0.8, 0.3, 0.0, 0.0>, color rgbft <0.2, 0.3, 0.9, 0.0, 0.0>
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <0.9063077870366499, 0.0, 0.42261826174069944, 0.109381654946615, 0.9659258262890683, -0.23456971600980447, -0.40821789367673483, 0.25881904510252074, 0.875426098065593, 2.9, -0.7, 6.5>
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

// "gradient" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <0.8660254037844387, 0.49999999999999994, -0.0, -0.49999999999999994, 0.8660254037844387, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
  texture {
    pigment {
      gradient <0.0, 1.0, -0.0>
      color_map {
        [0.0 color rgbft <0.9, 0.1, 0.1, 0.0, 0.0>]
        [0.5 color rgbft <0.95, 0.9, 0.2, 0.0, 0.0>]
        [1.0 color rgbft <0.1, 0.2, 0.9, 0.0, 0.0>]
      }
      frequency 2.0
      matrix <0.8660254037844387, 0.49999999999999994, -0.0, -0.49999999999999994, 0.8660254037844387, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
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

// "radial" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 0.5000000000000001, -0.8660254037844386, -0.0, 0.8660254037844386, 0.5000000000000001, -1.3, -0.4, 5.0>
  texture {
    pigment {
      radial
      color_map {
        [0.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
        [1.0 color rgbft <0.1, 0.4, 0.2, 0.0, 0.0>]
      }
      frequency 8.0
      sine_wave
      matrix <1.0, 0.0, -0.0, 0.0, 0.5000000000000001, -0.8660254037844386, -0.0, 0.8660254037844386, 0.5000000000000001, -1.3, -0.4, 5.0>
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

// "onion" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
  texture {
    pigment {
      onion
      color_map {
        [0.0 color rgbft <0.2, 0.1, 0.5, 0.0, 0.0>]
        [0.5 color rgbft <0.9, 0.6, 0.2, 0.0, 0.0>]
        [0.5 color rgbft <0.1, 0.6, 0.6, 0.0, 0.0>]
        [1.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
      }
      triangle_wave
      matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.3, -0.4>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, -0.4, 5.0>
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

// "leopard" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
  texture {
    pigment {
      leopard
      color_map {
        [0.0 color rgbft <0.9, 0.7, 0.3, 0.0, 0.0>]
        [0.3 color rgbft <0.9, 0.7, 0.3, 0.0, 0.0>]
        [0.6 color rgbft <0.15, 0.1, 0.05, 0.0, 0.0>]
      }
      cubic_wave
      matrix <0.12, 0.0, -0.0, 0.0, 0.12, -0.0, -0.0, -0.0, 0.12, 0.0, 0.0, -0.0>
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

// "spiral1" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 0.3420201433256688, 0.9396926207859083, -0.0, -0.9396926207859083, 0.3420201433256688, -1.9, 0.9, 6.0>
  texture {
    pigment {
      spiral1 3
      color_map {
        [0.0 color rgbft <0.1, 0.1, 0.3, 0.0, 0.0>]
        [1.0 color rgbft <0.9, 0.9, 1.0, 0.0, 0.0>]
      }
      phase 0.25
      scallop_wave
      matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 0.3420201433256688, 0.9396926207859083, -0.0, -0.9396926207859083, 0.3420201433256688, -1.9, 0.9, 6.0>
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

// "spiral2" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.5, 0.9, 6.0>
  texture {
    pigment {
      spiral2 2
      color_map {
        [0.0 color rgbft <0.8, 0.2, 0.6, 0.0, 0.0>]
        [0.7 color rgbft <0.95, 0.95, 0.9, 0.0, 0.0>]
        [1.0 color rgbft <0.2, 0.5, 0.2, 0.0, 0.0>]
      }
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.8, 0.0, 0.0, -0.0>
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

// "see_through" sphere
sphere { <0.0, 0.0, -0.0>, 0.7
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, 0.9, 6.0>
  texture {
    pigment {
      gradient <1.0, 0.0, -0.0>
      color_map {
        [0.0 color rgbft <1.0, 0.2, 0.2, 0.8, 0.0>]
        [0.45 color rgbft <1.0, 1.0, 1.0, 0.0, 0.9>]
        [0.55 color rgbft <0.1, 0.1, 0.8, 0.0, 0.0>]
        [1.0 color rgbft <0.2, 1.0, 0.2, 0.5, 0.3>]
      }
      matrix <0.7, 0.0, -0.0, 0.0, 0.7, -0.0, -0.0, -0.0, 0.7, -0.2, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, 0.9, 6.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.6 phong_size 60.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

