// POV-Ray 3.7 scene written by `prism export pov` from area_grid.toml; regenerate, do not edit.
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

background { rgb <0.3, 0.35, 0.45> }

camera {
  perspective
  location <0.0, 1.0, -1.5>
  direction <0.0, -0.2300254539289697, 0.9731846127764102>
  up <0.0, 1.013215687030718, 0.23948734420726064>
  right <0.9999999999999999, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-2.5, 3.0, 2.5>, color rgb <1.0, 1.0, 1.0>
  area_light <2.0, 0.0, -0.0>, <0.0, 0.0, -2.0>, 5, 5 adaptive 100
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.78, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.75 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "wall" plane
plane { <0.0, 0.0, -1.0>, -7.0
  texture {
    pigment { rgbft <0.7, 0.75, 0.8, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.75 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.0, -0.4, 4.0>
  texture {
    pigment { rgbft <0.85, 0.3, 0.2, 0.0, 0.0> }
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

// "tower" box
box { <0.6, -1.0, 5.0>, <1.2, 0.8, 4.4>
  texture {
    pigment { rgbft <0.3, 0.6, 0.85, 0.0, 0.0> }
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

// "sign" disc
disc { <0.0, 0.5, 5.5>, <0.0, 0.2873478855663454, -0.9578262852211513>, 0.45
  texture {
    pigment { rgbft <0.9, 0.85, 0.3, 0.0, 0.0> }
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

