// POV-Ray 3.7 scene written by `prism export pov` from layered.toml; regenerate, do not edit.
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
  location <0.0, 1.2, 1.0>
  direction <0.0, -0.27195700522594757, 0.962309403107199>
  up <0.0, 1.0018931353874518, 0.2831437121747147>
  right <0.9999999999999999, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
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
  texture {
    pigment {
      spotted
      color_map {
        [0.0 color rgbft <1.0, 1.0, 1.0, 0.0, 1.0>]
        [0.45 color rgbft <1.0, 1.0, 1.0, 0.0, 1.0>]
        [0.6 color rgbft <0.2, 0.5, 0.2, 0.3, 0.2>]
        [1.0 color rgbft <0.1, 0.3, 0.1, 0.0, 0.0>]
      }
      matrix <0.4, 0.0, -0.0, 0.0, 0.4, -0.0, -0.0, -0.0, 0.4, 0.0, 0.0, -0.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.8 phong_size 30.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "wall" plane
plane { <0.0, 0.0, -1.0>, -10.0
  texture {
    pigment { rgbft <0.7, 0.75, 0.85, 0.0, 0.0> }
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

// "three_layers" sphere
sphere { <0.0, 0.0, -0.0>, 0.75
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.9, -0.25, 5.2>
  texture {
    pigment { rgbft <0.8, 0.15, 0.1, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  texture {
    pigment {
      gradient <0.0, 1.0, -0.0>
      color_map {
        [0.0 color rgbft <0.95, 0.9, 0.3, 0.0, 0.0>]
        [0.4 color rgbft <0.95, 0.9, 0.3, 0.0, 0.0>]
        [0.5 color rgbft <1.0, 1.0, 1.0, 0.0, 1.0>]
        [1.0 color rgbft <1.0, 1.0, 1.0, 0.0, 1.0>]
      }
      frequency 4.0
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.9, -0.25, 5.2>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.15, 0.15, 0.15>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 1.0> }
    normal {
      bumps 0.4
      matrix <0.15, 0.0, -0.0, 0.0, 0.15, -0.0, -0.0, -0.0, 0.15, 0.0, 0.0, -0.0>
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.9, -0.25, 5.2>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.9 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.15, 0.15, 0.15>, rgb <0.15, 0.15, 0.15> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "coated_glass" box
box { <-0.6, -0.6, 0.6>, <0.6, 0.6, -0.6>
  matrix <0.7544065067354889, 0.133022221559489, 0.6427876096865393, 0.11014805529444444, 0.9397111195372712, -0.3237443709670646, -0.6470998597666425, 0.3150366651508782, 0.6942720440148838, 0.0, -0.1, 5.6>
  texture {
    pigment { rgbft <0.6, 0.8, 1.0, 0.85, 0.0> }
    normal {
      dents 0.6
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <0.7544065067354889, 0.133022221559489, 0.6427876096865393, 0.11014805529444444, 0.9397111195372712, -0.3237443709670646, -0.6470998597666425, 0.3150366651508782, 0.6942720440148838, 0.0, -0.1, 5.6>
    }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.1 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.1, 0.1, 0.1>, rgb <0.1, 0.1, 0.1> falloff 1.0 exponent 1.0 metallic 0.0 }
    }
  }
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 0.8> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.6 roughness 0.01
      metallic 0.0
      reflection { rgb <0.05, 0.05, 0.05>, rgb <0.6, 0.6, 0.6> falloff 3.0 exponent 1.0 metallic 0.0 }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "tinted_box" box
box { <-0.5, -0.5, 0.5>, <0.5, 0.5, -0.5>
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 1.9, -0.5, 5.0>
  texture {
    pigment { rgbft <1.0, 0.5, 0.2, 0.7, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.4 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  texture {
    pigment {
      checker color rgbft <0.2, 0.3, 0.9, 0.6, 0.0>, color rgbft <1.0, 1.0, 1.0, 0.0, 0.9>
      matrix <0.25, 0.0, -0.0, 0.0, 0.25, -0.0, -0.0, -0.0, 0.25, 0.0, 0.0, -0.0>
      matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 1.9, -0.5, 5.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

