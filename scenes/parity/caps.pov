// POV-Ray 3.7 scene written by `prism export pov` from caps.toml; regenerate, do not edit.
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

background { rgb <0.5, 0.6, 0.8> }

camera {
  perspective
  location <0.0, 1.2, -2.0>
  direction <0.0, -0.25873608522408353, 0.965948051503245>
  up <0.0, 0.7031526771892356, 0.18834446710425956>
  right <1.0, -0.0, -0.0> * 0.7279404685324047 * image_width / image_height
}

light_source { <-3.0, 4.0, -1.0>, color rgb <1.0, 1.0, 1.0>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.7, 0.7, 0.65, 0.0, 0.0> }
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

// "closed_cylinder" cylinder
cylinder { <-2.3, -0.55, 3.4>, <-1.5, -0.15, 2.5>, 0.4
  texture {
    pigment { rgbft <0.8, 0.2, 0.2, 0.0, 0.0> }
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

// "frustum" cone
cone { <-0.6, -0.9, 3.8>, 0.6, <-0.35, -0.05, 3.2>, 0.3
  texture {
    pigment { rgbft <0.9, 0.7, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.3 roughness 0.02
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "tube" cylinder
cylinder { <0.7, -0.65, 4.2>, <1.2, -0.35, 3.1>, 0.35 open
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

// "pointed_cone" cone
cone { <2.3, -0.9, 4.3>, 0.45, <2.5, 0.4, 3.7>, 0.0
  texture {
    pigment { rgbft <0.3, 0.4, 0.9, 0.0, 0.0> }
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

// "washer" disc
disc { <0.4, 0.45, 4.8>, <0.17609018126512477, 0.4402254531628119, -0.8804509063256238>, 0.6, 0.25
  texture {
    pigment { rgbft <0.85, 0.85, 0.85, 0.0, 0.0> }
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

