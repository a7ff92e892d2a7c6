// POV-Ray 3.7 scene written by `prism export pov` from pigment_map.toml; regenerate, do not edit.
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
      gradient <1.0, 0.0, -0.0>
      pigment_map {
        [0.0 checker color rgbft <0.9, 0.88, 0.8, 0.0, 0.0>, color rgbft <0.25, 0.3, 0.4, 0.0, 0.0>
          matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>]
        [0.4 color rgbft <0.9, 0.2, 0.1, 0.0, 0.0>]
        [0.5 color rgbft <0.95, 0.85, 0.2, 0.0, 0.0>]
        [0.5 color rgbft <0.1, 0.3, 0.8, 0.0, 0.0>]
        [1.0 checker color rgbft <0.2, 0.6, 0.3, 0.0, 0.0>, color rgbft <0.95, 0.95, 0.9, 0.0, 0.0>
          matrix <0.1767766952966369, 0.0, 0.17677669529663687, 0.0, 0.25, -0.0, -0.17677669529663687, -0.0, 0.1767766952966369, 0.0, 0.0, -0.0>]
      }
      matrix <6.0, 0.0, -0.0, 0.0, 6.0, -0.0, -0.0, -0.0, 6.0, -3.0, 0.0, -0.0>
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

// "backdrop" plane
plane { <0.0, 0.0, -1.0>, -9.0
  texture {
    pigment {
      checker color rgbft <0.85, 0.8, 0.7, 0.0, 0.0>, color rgbft <0.3, 0.2, 0.2, 0.0, 0.0>
      matrix <0.8, 0.0, -0.0, 0.0, 0.8, -0.0, -0.0, -0.0, 0.8, 0.0, 0.0, -0.0>
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

// "noise" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.3, -0.4, 5.0>
  texture {
    pigment {
      bozo
      turbulence <0.4, 0.4, 0.4> octaves 3
      pigment_map {
        [0.2 wrinkles
          turbulence <0.5, 0.2, 0.3>
          color_map {
            [0.0 color rgbft <0.1, 0.1, 0.3, 0.0, 0.0>]
            [1.0 color rgbft <0.9, 0.8, 0.5, 0.0, 0.0>]
          }
          matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>]
        [0.7 gradient <0.0, 1.0, -0.0>
          pigment_map {
            [0.0 color rgbft <0.8, 0.1, 0.1, 0.0, 0.0>]
            [1.0 spotted
              color_map {
                [0.0 color rgbft <0.1, 0.6, 0.2, 0.0, 0.0>]
                [1.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.0>]
              }
              matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
          }
          frequency 4.0]
      }
      matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.3, -0.4, 5.0>
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

// "see_through" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.8, -0.3, 5.5>
  texture {
    pigment {
      onion
      pigment_map {
        [0.0 color rgbft <1.0, 1.0, 1.0, 0.0, 0.8>]
        [0.5 gradient <0.0, 1.0, -0.0>
          color_map {
            [0.0 color rgbft <1.0, 0.3, 0.2, 0.7, 0.0>]
            [1.0 color rgbft <0.2, 0.2, 0.9, 0.0, 0.0>]
          }]
        [1.0 color rgbft <0.2, 0.9, 0.3, 0.5, 0.2>]
      }
      matrix <0.25, 0.0, -0.0, 0.0, 0.25, -0.0, -0.0, -0.0, 0.25, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.8, -0.3, 5.5>
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

// "transformed" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <0.901067248717891, 0.0, 0.6309340799861507, 0.2157921644659122, 1.0336618828644994, -0.30818314955255904, -0.5928840991653319, 0.37622215765823563, 0.846726244452063, 0.7, -0.3, 5.2>
  texture {
    pigment {
      radial
      pigment_map {
        [0.0 checker color rgbft <0.9, 0.9, 0.9, 0.0, 0.0>, color rgbft <0.6, 0.1, 0.1, 0.0, 0.0>
          matrix <0.1299038105676658, 0.07499999999999998, -0.0, -0.07499999999999998, 0.1299038105676658, -0.0, -0.0, -0.0, 0.15, 0.05, 0.0, -0.0>]
        [0.5 color rgbft <0.95, 0.8, 0.2, 0.0, 0.0>]
        [1.0 gradient <1.0, 1.0, -0.0>
          color_map {
            [0.0 color rgbft <0.1, 0.2, 0.6, 0.0, 0.0>]
            [1.0 color rgbft <0.8, 0.9, 1.0, 0.0, 0.0>]
          }
          matrix <0.1532088886237956, 0.0, 0.12855752193730785, 0.0, 0.2, -0.0, -0.12855752193730785, -0.0, 0.1532088886237956, 0.0, 0.0, -0.0>]
      }
      frequency 3.0
      matrix <0.9396926207859084, 0.3420201433256687, -0.0, -0.23395555688102201, 0.6427876096865395, -1.8793852415718166, -0.3213938048432696, 0.883022221559489, 0.3420201433256688, 0.1, 0.2, -0.0>
      matrix <0.901067248717891, 0.0, 0.6309340799861507, 0.2157921644659122, 1.0336618828644994, -0.30818314955255904, -0.5928840991653319, 0.37622215765823563, 0.846726244452063, 0.7, -0.3, 5.2>
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

// "image_entry" sphere
sphere { <0.0, 0.0, -0.0>, 0.55
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.2, -0.45, 5.0>
  texture {
    pigment {
      gradient <0.0, 1.0, -0.0>
      pigment_map {
        [0.3 image_map { png "image_map.png" map_type 1 interpolate 2 }]
        [0.7 leopard
          color_map {
            [0.0 color rgbft <0.9, 0.7, 0.3, 0.0, 0.0>]
            [0.6 color rgbft <0.15, 0.1, 0.05, 0.0, 0.0>]
          }
          matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
      }
      matrix <1.2, 0.0, -0.0, 0.0, 1.2, -0.0, -0.0, -0.0, 1.2, 0.0, -0.6, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.2, -0.45, 5.0>
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

// "marble" box
box { <-0.5, -0.3, 0.5>, <0.5, 0.3, -0.5>
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, -1.6, 0.8, 6.5>
  texture {
    pigment {
      marble
      turbulence <0.8, 0.8, 0.8>
      pigment_map {
        [0.0 checker color rgbft <0.95, 0.95, 0.95, 0.0, 0.0>, color rgbft <0.2, 0.2, 0.2, 0.0, 0.0>
          matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
        [1.0 color rgbft <0.5, 0.2, 0.6, 0.0, 0.0>]
      }
      matrix <0.6, 0.0, -0.0, 0.0, 0.6, -0.0, -0.0, -0.0, 0.6, 0.0, 0.0, -0.0>
      matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, -1.6, 0.8, 6.5>
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

// "checker_pigments" box
box { <-0.5, -0.4, 0.1>, <0.5, 0.4, -0.1>
  matrix <0.9396926207859084, 0.0, -0.3420201433256687, 0.0, 1.0, -0.0, 0.3420201433256687, -0.0, 0.9396926207859084, 1.6, 0.8, 6.5>
  texture {
    pigment {
      checker
        pigment {
          gradient <1.0, 1.0, -0.0>
          color_map {
            [0.0 color rgbft <0.9, 0.5, 0.1, 0.0, 0.0>]
            [1.0 color rgbft <0.2, 0.1, 0.5, 0.0, 0.0>]
          }
          matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
        },
        pigment {
          radial
          color_map {
            [0.0 color rgbft <0.95, 0.95, 0.9, 0.0, 0.0>]
            [1.0 color rgbft <0.1, 0.4, 0.2, 0.0, 0.0>]
          }
          frequency 10.0
        }
      turbulence <0.1, 0.1, 0.1>
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <0.9396926207859084, 0.0, -0.3420201433256687, 0.0, 1.0, -0.0, 0.3420201433256687, -0.0, 0.9396926207859084, 1.6, 0.8, 6.5>
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

