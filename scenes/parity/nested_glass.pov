// POV-Ray 3.7 scene written by `prism export pov` from nested_glass.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 12
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.5, 0.6, 0.8> }

camera {
  perspective
  location <0.0, 0.3, -1.0>
  direction <0.0, -0.07974522228289001, 0.9968152785361251>
  up <0.0, 0.9296451962946062, 0.0743716157035685>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <-2.0, 4.0, -0.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.75, 0.72, 0.6, 0.0, 0.0> }
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
plane { <0.0, 0.0, -1.0>, -8.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
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

// "stripe_red" box
box { <-4.0, -1.0, 7.9>, <4.0, -0.4, 7.8>
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
  interior { ior 1.0 }
}

// "stripe_blue" box
box { <-4.0, 0.2, 7.9>, <4.0, 0.8, 7.8>
  texture {
    pigment { rgbft <0.1, 0.2, 0.8, 0.0, 0.0> }
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

// "post" cylinder
cylinder { <0.3, -1.0, 6.0>, <0.3, 2.0, 6.0>, 0.15
  texture {
    pigment { rgbft <0.2, 0.7, 0.2, 0.0, 0.0> }
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

// "outer" sphere
sphere { <0.0, 0.0, -0.0>, 0.9
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.0, -0.1, 4.0>
  texture {
    pigment { rgbft <0.95, 1.0, 0.97, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.7 phong_size 150.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "drop" sphere
sphere { <0.0, 0.0, -0.0>, 0.4
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.15, 0.1, 3.9>
  texture {
    pigment { rgbft <0.7, 0.85, 1.0, 0.85, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.33 }
}

// "bubble" sphere
sphere { <0.0, 0.0, -0.0>, 0.2
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.65, -0.35, 3.75>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 1.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.0 }
}

// "left_of_pair" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.0, -0.35, 4.2>
  texture {
    pigment { rgbft <0.95, 1.0, 0.97, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.7 phong_size 150.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "right_of_pair" sphere
sphere { <0.0, 0.0, -0.0>, 0.55
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.6, -0.3, 4.5>
  texture {
    pigment { rgbft <1.0, 0.95, 0.9, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.8 }
}

