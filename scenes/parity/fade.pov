// POV-Ray 3.7 scene written by `prism export pov` from fade.toml; regenerate, do not edit.
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

background { rgb <0.55, 0.6, 0.7> }

camera {
  perspective
  location <0.0, 1.2, -1.5>
  direction <0.0, -0.279329540830131, 0.9601952966035754>
  up <0.0, 0.9996920670131647, 0.2908195104038297>
  right <0.9999999999999999, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-1.0, 4.0, 2.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.9, 0.88, 0.85, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 1.0
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
    pigment { rgbft <0.7, 0.75, 0.8, 0.0, 0.0> }
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

// "amber" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.2, -0.4, 4.0>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.95, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.5 phong_size 100.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.3 fade_distance 0.4 fade_power 2.0 fade_color rgb <1.0, 0.5, 0.1> }
}

// "ink" sphere
sphere { <0.0, 0.0, -0.0>, 0.55
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.2, -0.45, 4.4>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 0.95> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.05 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 fade_distance 0.5 fade_power 1001.0 fade_color rgb <0.2, 0.4, 0.9> }
}

// "jelly" box
box { <1.0, -0.98, 4.6>, <1.8, -0.1, 3.8>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.9, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.05 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.1 fade_distance 0.6 fade_power 1.0 fade_color rgb <0.2, 0.8, 0.3> }
}

