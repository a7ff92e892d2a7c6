// POV-Ray 3.7 scene written by `prism export pov` from light_edges.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 -A
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <0.6, 0.6, 0.6>
}

background { rgb <0.3, 0.35, 0.5> }

camera {
  perspective
  location <0.0, 1.2, -2.0>
  direction <0.0, -0.2466792806349307, 0.969097173922942>
  up <0.0, 1.0089601150541971, 0.2568262111047047>
  right <1.0, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <1.6, 3.0, 2.5>, color rgb <0.9, 0.8, 0.5>
  spotlight point_at <1.6, -1.0, 4.0> radius 25.0 falloff 15.0 tightness 0.0
}

light_source { <0.4, 3.0, 2.5>, color rgb <0.45, 0.45, 0.45>
  area_light <3.0, 0.0, -0.0>, <0.0, 0.0, -3.0>, 2, 2 adaptive 100 circular orient
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.75, 0.0, 0.0> }
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
plane { <0.0, 0.0, -1.0>, -6.0
  texture {
    pigment { rgbft <0.6, 0.65, 0.8, 0.0, 0.0> }
    finish {
      ambient rgb <0.2, 0.2, 0.2> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "sheet" rectangle
polygon { 5, <-0.8, -0.6, -0.0>, <0.8, -0.6, -0.0>, <0.8, 0.6, -0.0>, <-0.8, 0.6, -0.0>, <-0.8, -0.6, -0.0>
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.5, 0.0, 3.0>
  texture {
    pigment { rgbft <0.9, 0.95, 1.0, 0.2, 0.7> }
    finish {
      ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.1 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
  no_shadow
}

// "red_card" rectangle
polygon { 5, <-0.3, -0.45, -0.0>, <0.3, -0.45, -0.0>, <0.3, 0.45, -0.0>, <-0.3, 0.45, -0.0>, <-0.3, -0.45, -0.0>
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.85, 0.0, 3.00005>
  texture {
    pigment { rgbft <0.9, 0.15, 0.1, 0.0, 0.0> }
    finish {
      ambient rgb <0.6, 0.6, 0.6> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.4 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
  no_shadow
}

// "green_card" rectangle
polygon { 5, <-0.3, -0.45, -0.0>, <0.3, -0.45, -0.0>, <0.3, 0.45, -0.0>, <-0.3, 0.45, -0.0>, <-0.3, -0.45, -0.0>
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.15, 0.0, 3.0003>
  texture {
    pigment { rgbft <0.1, 0.8, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.6, 0.6, 0.6> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.4 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
  no_shadow
}

// "ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.25
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.6, 0.6, 3.5>
  texture {
    pigment { rgbft <0.9, 0.6, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 30.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

