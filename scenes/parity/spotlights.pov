// POV-Ray 3.7 scene written by `prism export pov` from spotlights.toml; regenerate, do not edit.
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
  location <0.0, 1.0, 0.5>
  direction <0.0, -0.33500966765480555, 0.9422146902791406>
  up <0.0, 1.0879758101341634, 0.38683584360325807>
  right <1.0, -0.0, -0.0> * 1.1547005383792515 * image_width / image_height
}

light_source { <-0.8, 2.8, 2.5>, color rgb <1.0, 1.0, 1.0>
  spotlight point_at <-0.8, -1.0, 4.5> radius 12.0 falloff 18.0 tightness 0.0
}

light_source { <2.5, 2.5, 3.0>, color rgb <1.0, 0.3, 0.2>
  spotlight point_at <1.1, -1.0, 4.7> radius 20.0 falloff 35.0 tightness 20.0
}

light_source { <-3.0, 2.5, 6.5>, color rgb <0.2, 0.4, 1.0>
  spotlight point_at <-1.0, -1.0, 6.0> radius 25.0 falloff 40.0 tightness 2.0
  fade_distance 3.0 fade_power 2.0
}

light_source { <0.0, 2.5, 1.0>, color rgb <0.15, 0.15, 0.15>
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

// "ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.8, -0.4, 4.5>
  texture {
    pigment { rgbft <0.9, 0.9, 0.9, 0.0, 0.0> }
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

// "crate" box
box { <0.6, -1.0, 5.2>, <1.6, 0.0, 4.2>
  texture {
    pigment { rgbft <0.8, 0.7, 0.5, 0.0, 0.0> }
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

