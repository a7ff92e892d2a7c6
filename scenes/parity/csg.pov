// POV-Ray 3.7 scene written by `prism export pov` from csg.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 8
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.55, 0.65, 0.85> }

camera {
  perspective
  location <0.0, 1.2, -0.0>
  direction <0.0, -0.31622776601683794, 0.9486832980505138>
  up <0.0, 0.8447620351303929, 0.28158734504346433>
  right <1.0, -0.0, -0.0> * 0.8904573706170724 * image_width / image_height
}

light_source { <2.0, 5.0, -1.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.6, 0.6, 0.55, 0.0, 0.0> }
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

// "union" union
union {
  sphere { <0.0, 0.0, -0.0>, 0.6
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.3, 0.0, -0.0>
  }
  sphere { <0.0, 0.0, -0.0>, 0.5
    texture {
      pigment { rgbft <0.2, 0.7, 0.25, 0.0, 0.0> }
      finish {
        ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.7 brilliance 1.0
        phong 0.0 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
      }
    }
    interior { ior 1.0 }
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.35, 0.1, -0.0>
  }
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -3.0, -0.2, 5.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 0.7> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "merge" merge
merge {
  sphere { <0.0, 0.0, -0.0>, 0.6
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.3, 0.0, -0.0>
  }
  sphere { <0.0, 0.0, -0.0>, 0.5
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.35, 0.1, -0.0>
  }
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.2, -0.2, 5.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.85, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.8 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "lens" intersection
intersection {
  sphere { <0.0, 0.0, -0.0>, 1.0
    texture {
      pigment { rgbft <0.2, 0.3, 0.8, 0.0, 0.0> }
      finish {
        ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.7 brilliance 1.0
        phong 0.3 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
      }
    }
    interior { ior 1.0 }
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.6, 0.0, -0.0>
  }
  sphere { <0.0, 0.0, -0.0>, 1.0
    texture {
      pigment { rgbft <0.8, 0.15, 0.1, 0.0, 0.0> }
      finish {
        ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.7 brilliance 1.0
        phong 0.5 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
      }
    }
    interior { ior 1.0 }
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.6, 0.0, -0.0>
  }
  matrix <0.9063077870366499, 0.0, -0.42261826174069944, 0.0, 1.0, -0.0, 0.42261826174069944, -0.0, 0.9063077870366499, 0.6, 0.0, 5.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 0.0> }
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

// "glass_difference" difference
difference {
  box { <-0.6, -0.6, 0.6>, <0.6, 0.6, -0.6>
  }
  sphere { <0.0, 0.0, -0.0>, 0.75
  }
  cylinder { <0.0, 0.0, 1.0>, <0.0, 0.0, -1.0>, 0.25
    texture {
      pigment { rgbft <0.8, 0.15, 0.1, 0.0, 0.0> }
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
  matrix <0.9063077870366499, 0.0, -0.42261826174069944, -0.144543958452599, 0.9396926207859084, -0.30997551921944466, 0.39713126196710286, 0.3420201433256687, 0.8516507396391465, 2.6, -0.3, 5.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.85, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.8 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "nested" union
union {
  box { <-0.25, -0.4, 0.25>, <0.25, 0.0, -0.25>
    texture {
      pigment { rgbft <0.8, 0.15, 0.1, 0.0, 0.0> }
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
  difference {
    sphere { <0.0, 0.0, -0.0>, 0.35
      texture {
        pigment { rgbft <0.2, 0.3, 0.8, 0.0, 0.0> }
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
    sphere { <0.0, 0.0, -0.0>, 0.3
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.25, 0.1, -0.2>
      inverse
    }
    matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.0, 0.3, -0.0>
  }
  matrix <0.766044443118978, 0.0, 0.6427876096865393, 0.0, 0.8, -0.0, -0.6427876096865393, -0.0, 0.766044443118978, -0.6, -0.6, 2.8>
  texture {
    pigment { rgbft <0.2, 0.7, 0.25, 0.0, 0.0> }
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

