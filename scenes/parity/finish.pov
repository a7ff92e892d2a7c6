// POV-Ray 3.7 scene written by `prism export pov` from finish.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <0.9, 0.8, 1.2>
}

background { rgb <0.2, 0.25, 0.35> }

camera {
  perspective
  location <0.0, 0.5, -1.5>
  direction <0.0, -0.12625427967391514, 0.991997911723619>
  up <0.0, 0.9251524462209796, 0.11774667497357921>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <-2.0, 3.0, -0.0>, color rgb <1.0, 0.9, 0.8>
}

light_source { <3.0, 1.0, 2.0>, color rgb <0.3, 0.4, 0.7>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.6, 0.6, 0.6, 0.0, 0.0> }
    finish {
      ambient rgb <0.2, 0.1, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "lamp" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.0, -0.2, 4.5>
  texture {
    pigment { rgbft <1.0, 0.8, 0.4, 0.0, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <1.2, 1.0, 0.8>
      diffuse 0.2 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "bright" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.9, -0.55, 4.0>
  texture {
    pigment { rgbft <0.2, 0.5, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.9 brilliance 4.0
      phong 0.0 phong_size 40.0
      specular 0.8 roughness 0.001
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "rough" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.15, -0.55, 4.0>
  texture {
    pigment { rgbft <0.9, 0.3, 0.3, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 0.5
      phong 0.0 phong_size 40.0
      specular 0.6 roughness 0.2
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "glossy" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.2, -0.55, 4.0>
  texture {
    pigment { rgbft <0.3, 0.8, 0.3, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 1.0 phong_size 300.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "satin" sphere
sphere { <0.0, 0.0, -0.0>, 0.35
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 2.1, -0.65, 4.8>
  texture {
    pigment { rgbft <0.8, 0.8, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.9 phong_size 8.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

