// POV-Ray 3.7 scene written by `prism export pov` from text.toml; regenerate, do not edit.
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
  location <0.0, 1.1, -1.0>
  direction <0.0, -0.19611613513818404, 0.9805806756909202>
  up <0.0, 0.873165290153649, 0.1746330580307298>
  right <0.9999999999999999, -0.0, -0.0> * 0.8904573706170724 * image_width / image_height
}

light_source { <3.0, 5.0, -2.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.75, 0.75, 0.7, 0.0, 0.0> }
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

// "prism" text
text { ttf "../../assets/fonts/DejaVuSans.ttf" "Prism" 0.3, <0.0, 0.0, -0.0>
  matrix <1.1, 0.0, -0.0, 0.0, 1.1, -0.0, -0.0, -0.0, 1.1, -1.5, 0.6, 5.5>
  texture {
    pigment { rgbft <0.85, 0.25, 0.15, 0.0, 0.0> }
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

// "pov_ray" text
text { ttf "../../assets/fonts/DejaVuSans.ttf" "POV-Ray" 0.4, <0.0, 0.0, -0.0>
  matrix <0.5362311101832846, 0.0, 0.4499513267805774, 0.0, 0.7, -0.0, -0.4499513267805774, -0.0, 0.5362311101832846, -2.9, -0.95, 3.4>
  texture {
    pigment { rgbft <0.25, 0.4, 0.85, 0.0, 0.0> }
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

// "offset" text
text { ttf "../../assets/fonts/DejaVuSans.ttf" "offset" 0.2, <0.08, 0.1, -0.0>
  matrix <0.5437846722219899, 0.0, -0.2535709570444197, 0.1071637170940382, 0.5437846722219899, 0.2298133329356934, 0.2298133329356934, -0.2535709570444197, 0.49283628290596176, 1.05, -0.45, 4.4>
  texture {
    pigment { rgbft <0.3, 0.75, 0.3, 0.0, 0.0> }
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

// "engraved" difference
difference {
  box { <-0.1, -0.15, 0.3>, <1.3, 0.75, -0.0>
  }
  text { ttf "../../assets/fonts/DejaVuSans.ttf" "AVO" 0.3, <0.0, 0.0, -0.0>
    texture {
      pigment { rgbft <0.2, 0.2, 0.25, 0.0, 0.0> }
      finish {
        ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.8 brilliance 1.0
        phong 0.0 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
      }
    }
    interior { ior 1.0 }
    matrix <0.6, 0.0, -0.0, 0.0, 0.6, -0.0, -0.0, -0.0, 0.6, 0.0, 0.0, -0.1>
  }
  matrix <1.0, 0.0, -0.0, 0.0, 0.984807753012208, 0.17364817766693033, -0.0, -0.17364817766693033, 0.984807753012208, -0.8, -0.8, 2.5>
  texture {
    pigment { rgbft <0.9, 0.8, 0.55, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 20.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

