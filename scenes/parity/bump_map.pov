// POV-Ray 3.7 scene written by `prism export pov` from bump_map.toml; regenerate, do not edit.
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
    pigment { rgbft <0.8, 0.78, 0.7, 0.0, 0.0> }
    normal {
      bump_map { png "image_map.png" map_type 0 interpolate 2 bump_size 3.0 }
      matrix <4.0, 0.0, -0.0, 0.0, 2.4492935982947064e-16, -4.0, -0.0, 4.0, 2.4492935982947064e-16, 0.0, 0.0, -0.0>
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
    pigment { rgbft <0.7, 0.75, 0.85, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_grey.png" map_type 0 bump_size 1.5 }
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

// "spherical" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.6, -0.4, 5.0>
  texture {
    pigment { rgbft <0.9, 0.4, 0.2, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_grey.png" map_type 1 interpolate 3 bump_size -4.0 }
      matrix <6.123233995736766e-17, 0.0, -1.0, 0.0, 1.0, -0.0, 1.0, -0.0, 6.123233995736766e-17, 0.0, 0.0, -0.0>
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

// "cylindrical" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.4, 5.0>
  texture {
    pigment { rgbft <0.3, 0.7, 0.4, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_gamma.png" map_type 2 interpolate 4 bump_size 2.0 }
      matrix <1.0, 0.0, -0.0, 0.0, 1.2, -0.0, -0.0, -0.0, 1.0, 0.0, -0.6, -0.0>
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
      bump_map { png "image_map_rgb16.png" map_type 1 interpolate 2 bump_size 3.0 }
      matrix <6.123233995736766e-17, 0.0, -1.0, -0.3420201433256687, 0.9396926207859084, -2.094269368838496e-17, 0.9396926207859084, 0.3420201433256687, 5.753957801139251e-17, 0.0, 0.0, -0.0>
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

// "palette" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.4, 5.0>
  texture {
    pigment { rgbft <0.85, 0.85, 0.6, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_palette.png" map_type 1 bump_size 2.0 }
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

// "in_a_map" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
  texture {
    pigment { rgbft <0.4, 0.5, 0.9, 0.0, 0.0> }
    normal {
      gradient <0.0, 1.0, -0.0>
      normal_map {
        [0.3 bumps 0.8
          matrix <0.1, 0.0, -0.0, 0.0, 0.1, -0.0, -0.0, -0.0, 0.1, 0.0, 0.0, -0.0>]
        [0.7 bump_map { png "image_map.png" map_type 1 interpolate 2 bump_size 2.5 }
          matrix <6.123233995736766e-17, 0.0, -1.0, 0.0, 1.0, -0.0, 1.0, -0.0, 6.123233995736766e-17, 0.0, 0.0, -0.0>]
      }
      matrix <1.2, 0.0, -0.0, 0.0, 1.2, -0.0, -0.0, -0.0, 1.2, 0.0, -0.6, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.6, -0.4, 5.0>
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
    pigment { rgbft <0.9, 0.8, 0.5, 0.0, 0.0> }
    normal {
      bump_map { png "image_map.png" map_type 0 interpolate 2 once bump_size -2.0 }
      turbulence <0.05, 0.05, 0.05>
      matrix <0.8, 0.0, -0.0, 0.0, 0.8, -0.0, -0.0, -0.0, 0.8, -0.4, -0.4, -0.0>
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

// "indices" box
box { <-0.5, -0.5, 0.5>, <0.5, 0.5, -0.5>
  matrix <0.8660254037844387, 0.0, -0.49999999999999994, 0.17101007166283433, 0.9396926207859084, 0.29619813272602386, 0.46984631039295416, -0.3420201433256687, 0.8137976813493738, 1.3, 0.9, 6.0>
  texture {
    pigment { rgbft <0.8, 0.3, 0.6, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_palette.png" map_type 0 interpolate 2 use_index bump_size 0.3 }
      matrix <0.5, 0.0, -0.0, 0.0, 0.5, -0.0, -0.0, -0.0, 0.5, 0.0, 0.0, -0.0>
      matrix <0.8660254037844387, 0.0, -0.49999999999999994, 0.17101007166283433, 0.9396926207859084, 0.29619813272602386, 0.46984631039295416, -0.3420201433256687, 0.8137976813493738, 1.3, 0.9, 6.0>
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

// "indices_plain" box
box { <-0.3, -0.3, 0.3>, <0.3, 0.3, -0.3>
  matrix <0.9396926207859084, 0.0, 0.3420201433256687, 0.0, 1.0, -0.0, -0.3420201433256687, -0.0, 0.9396926207859084, 0.0, 1.0, 6.5>
  texture {
    pigment { rgbft <0.5, 0.8, 0.8, 0.0, 0.0> }
    normal {
      bump_map { png "image_map_palette.png" map_type 0 use_index bump_size 0.4 }
      matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>
      matrix <0.9396926207859084, 0.0, 0.3420201433256687, 0.0, 1.0, -0.0, -0.3420201433256687, -0.0, 0.9396926207859084, 0.0, 1.0, 6.5>
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

