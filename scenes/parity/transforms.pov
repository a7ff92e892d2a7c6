// POV-Ray 3.7 scene written by `prism export pov` from transforms.toml; regenerate, do not edit.
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

background { rgb <0.45, 0.5, 0.6> }

camera {
  perspective
  location <0.0, 1.5, -1.5>
  direction <0.0, -0.3110390604146255, 0.9503971290446889>
  up <0.0, 0.989490860639282, 0.323833372572856>
  right <1.0, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-2.0, 4.0, -0.5>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.78, 0.7, 0.0, 0.0> }
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

// "tilted" box
box { <-0.5, -0.5, 0.5>, <0.5, 0.5, -0.5>
  matrix <0.9680487409339185, 0.17069311166750883, 0.6882917236212552, 0.015009224691876141, 0.47974097834202906, -0.14008324979661774, -0.47215065423341873, 0.1945841849665834, 0.6158009050560458, -1.5, -0.3, 4.0>
  texture {
    pigment { rgbft <0.9, 0.3, 0.2, 0.0, 0.0> }
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

// "moon" sphere
sphere { <0.0, 0.0, -0.0>, 0.25
  matrix <0.9680487409339185, 0.17069311166750883, 0.6882917236212552, 0.015009224691876141, 0.47974097834202906, -0.14008324979661774, -0.47215065423341873, 0.1945841849665834, 0.6158009050560458, -1.4819889303697487, 0.27568917401043486, 3.831900100244059>
  texture {
    pigment { rgbft <0.9, 0.9, 0.3, 0.0, 0.0> }
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

// "sheared" cylinder
cylinder { <0.0, 0.0, -0.0>, <0.0, 1.0, -0.0>, 0.3
  matrix <1.0, 0.0, -0.0, 0.4, 1.2, 0.3, -0.0, -0.0, 1.0, 0.2, -1.0, 4.5>
  texture {
    pigment { rgbft <0.3, 0.7, 0.4, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.4 roughness 0.03
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "plate" disc
disc { <0.0, 0.0, -0.0>, <0.0, 1.0, -0.0>, 0.5
  matrix <0.9396926207859084, -0.3420201433256687, -0.0, 0.11697777844051101, 0.32139380484326974, -0.9396926207859083, 0.3213938048432696, 0.883022221559489, 0.3420201433256688, 1.5, -0.2, 4.0>
  texture {
    pigment { rgbft <0.3, 0.4, 0.9, 0.0, 0.0> }
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

// "flag" triangle
triangle { <0.0, 0.0, -0.0>, <1.0, 0.0, -0.0>, <0.0, 0.8, -0.0>
  matrix <0.9958577760546714, 0.0, -0.835623892592501, 0.0, 1.3, -0.0, 0.835623892592501, -0.0, 0.9958577760546714, 0.6, 0.3, 5.5>
  texture {
    pigment { rgbft <0.8, 0.4, 0.9, 0.0, 0.0> }
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

