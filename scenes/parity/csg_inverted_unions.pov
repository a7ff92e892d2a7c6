// POV-Ray 3.7 scene written by `prism export pov` from csg_inverted_unions.toml; regenerate, do not edit.
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
  location <0.0, 1.6, -0.5>
  direction <0.0, -0.33871946827274163, 0.9408874118687267>
  up <0.0, 0.8774860112320472, 0.315894964043537>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <2.0, 5.0, -1.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <-4.0, 3.0, -2.0>, color rgb <0.4, 0.4, 0.45>
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

// "drilled" difference
difference {
  box { <-0.6, -0.6, 0.6>, <0.6, 0.6, -0.6>
  }
  union {
    cylinder { <-1.0, 0.0, -0.0>, <1.0, 0.0, -0.0>, 0.35
      texture {
        pigment { rgbft <0.3, 0.5, 0.9, 0.0, 0.0> }
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
    cylinder { <0.0, -1.0, -0.0>, <0.0, 1.0, -0.0>, 0.35
      texture {
        pigment { rgbft <0.3, 0.5, 0.9, 0.0, 0.0> }
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
    cylinder { <0.0, 0.0, 1.0>, <0.0, 0.0, -1.0>, 0.35
      texture {
        pigment { rgbft <0.3, 0.5, 0.9, 0.0, 0.0> }
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
  }
  matrix <0.8191520442889918, 0.0, -0.573576436351046, -0.28678821817552297, 0.8660254037844387, -0.40957602214449584, 0.49673176489215404, 0.49999999999999994, 0.7094064799162225, -2.7, -0.1, 5.0>
  texture {
    pigment { rgbft <0.85, 0.6, 0.35, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 30.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "inverse_union" intersection
intersection {
  sphere { <0.0, 0.0, -0.0>, 0.75
  }
  union {
    box { <-0.3, -0.3, 1.0>, <1.0, 1.0, -1.0>
      texture {
        pigment { rgbft <0.2, 0.7, 0.3, 0.0, 0.0> }
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
    sphere { <0.0, 0.0, -0.0>, 0.45
      texture {
        pigment { rgbft <0.2, 0.7, 0.3, 0.0, 0.0> }
        finish {
          ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
          diffuse 0.7 brilliance 1.0
          phong 0.0 phong_size 40.0
          specular 0.0 roughness 0.05
          metallic 0.0
        }
      }
      interior { ior 1.0 }
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.2, 0.2, -0.2>
    }
    inverse
  }
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, -0.9, -0.25, 5.0>
  texture {
    pigment { rgbft <0.85, 0.6, 0.35, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 30.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "nested" difference
difference {
  box { <-0.6, -0.6, 0.6>, <0.6, 0.6, -0.6>
  }
  intersection {
    sphere { <0.0, 0.0, -0.0>, 0.8
      texture {
        pigment { rgbft <0.8, 0.2, 0.2, 0.0, 0.0> }
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
    union {
      cylinder { <-1.0, 0.0, -0.0>, <1.0, 0.0, -0.0>, 0.3
        texture {
          pigment { rgbft <0.8, 0.2, 0.2, 0.0, 0.0> }
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
      cylinder { <0.0, 0.0, 1.0>, <0.0, 0.0, -1.0>, 0.3
        texture {
          pigment { rgbft <0.8, 0.2, 0.2, 0.0, 0.0> }
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
    }
  }
  matrix <0.9063077870366499, 0.0, -0.42261826174069944, -0.144543958452599, 0.9396926207859084, -0.30997551921944466, 0.39713126196710286, 0.3420201433256687, 0.8516507396391465, 0.9, -0.3, 5.0>
  texture {
    pigment { rgbft <0.9, 1.0, 0.95, 0.0, 0.7> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.6 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "twice" difference
difference {
  sphere { <0.0, 0.0, -0.0>, 0.8
  }
  union {
    sphere { <0.0, 0.0, -0.0>, 0.5
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.25, 0.0, -0.0>
    }
    sphere { <0.0, 0.0, -0.0>, 0.5
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.25, 0.1, -0.0>
    }
    box { <-0.2, -0.9, 0.2>, <0.2, 0.0, -0.2>
    }
    inverse
  }
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.7, -0.2, 5.0>
  texture {
    pigment { rgbft <0.9, 1.0, 0.95, 0.0, 0.7> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.6 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "control" intersection
intersection {
  box { <-0.5, -0.45, 0.5>, <0.5, 0.45, -0.5>
  }
  union {
    sphere { <0.0, 0.0, -0.0>, 0.4
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.2, 0.0, -0.0>
    }
    sphere { <0.0, 0.0, -0.0>, 0.35
      matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.25, 0.05, -0.0>
    }
  }
  matrix <0.9396926207859084, 0.0, 0.3420201433256687, 0.0, 1.0, -0.0, -0.3420201433256687, -0.0, 0.9396926207859084, 0.0, -0.55, 2.6>
  texture {
    pigment { rgbft <0.9, 1.0, 0.95, 0.0, 0.7> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.2 brilliance 1.0
      phong 0.6 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

