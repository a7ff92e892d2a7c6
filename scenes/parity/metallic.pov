// POV-Ray 3.7 scene written by `prism export pov` from metallic.toml; regenerate, do not edit.
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

background { rgb <0.0, 0.0, 0.0> }

camera {
  perspective
  location <0.0, 0.4, 0.8>
  direction <0.0, -0.2113327925275389, 0.9774141654398674>
  up <0.0, 1.0176192185410566, 0.22002577698185008>
  right <1.0, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <1.0, 2.5, 2.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <-3.0, 2.0, 6.0>, color rgb <0.3, 0.3, 0.4>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
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

// "ceiling" plane
plane { <0.0, -1.0, -0.0>, -3.0
  texture {
    pigment { rgbft <0.9, 0.9, 0.9, 0.0, 0.0> }
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

// "left_wall" plane
plane { <1.0, 0.0, -0.0>, -4.0
  texture {
    pigment { rgbft <0.75, 0.25, 0.25, 0.0, 0.0> }
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

// "right_wall" plane
plane { <-1.0, 0.0, -0.0>, -4.0
  texture {
    pigment { rgbft <0.25, 0.75, 0.25, 0.0, 0.0> }
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

// "back_wall" plane
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

// "front_wall" plane
plane { <0.0, 0.0, 1.0>, -2.0
  texture {
    pigment { rgbft <0.3, 0.3, 0.8, 0.0, 0.0> }
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

// "gold" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.4, -0.4, 4.0>
  texture {
    pigment { rgbft <1.0, 0.75, 0.3, 0.0, 0.0> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.3 brilliance 1.0
      phong 0.8 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 1.0
      reflection { rgb <0.2, 0.2, 0.2>, rgb <0.8, 0.8, 0.8> falloff 2.0 exponent 1.0 metallic 1.0 }
    }
  }
  interior { ior 1.0 }
}

// "copper" box
box { <-0.5, -1.0, 5.0>, <0.5, -0.2, 4.0>
  texture {
    pigment { rgbft <0.95, 0.5, 0.35, 0.0, 0.0> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.4 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.7 roughness 0.01
      metallic 0.6
      reflection { rgb <0.1, 0.1, 0.1>, rgb <0.5, 0.5, 0.5> falloff 1.0 exponent 1.0 metallic 0.5 }
    }
  }
  interior { ior 1.0 }
}

// "soft_mirror" sphere
sphere { <0.0, 0.0, -0.0>, 0.55
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.3, -0.45, 4.2>
  texture {
    pigment { rgbft <0.8, 0.85, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.6, 0.6, 0.6>, rgb <0.6, 0.6, 0.6> falloff 1.0 exponent 2.0 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "chalk" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.1, 0.3, 5.5>
  texture {
    pigment { rgbft <0.9, 0.9, 0.85, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 3.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

