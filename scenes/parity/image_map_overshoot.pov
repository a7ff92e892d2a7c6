// POV-Ray 3.7 scene written by `prism export pov` from image_map_overshoot.toml; regenerate, do not edit.
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

background { rgb <0.2, 0.45, 0.3> }

camera {
  perspective
  location <0.0, 1.2, -3.4>
  direction <0.0, -0.25589256031628255, 0.9667052278615119>
  up <0.0, 0.9015641018605918, 0.23864932108074488>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <-3.0, 6.0, -5.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <4.0, 3.0, -3.0>, color rgb <0.3, 0.3, 0.3>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -0.6
  texture {
    pigment { rgbft <0.8, 0.8, 0.75, 0.0, 0.0> }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "wall" box
box { <0.0, 0.0, 0.01>, <1.0, 1.0, -0.01>
  matrix <2.0, 0.0, -0.0, 0.0, 1.6, -0.0, -0.0, -0.0, 1.0, -2.2, -0.5, 1.0>
  texture {
    pigment {
      image_map { png "image_map_palette.png" map_type 0 interpolate 3 once }
      matrix <2.0, 0.0, -0.0, 0.0, 1.6, -0.0, -0.0, -0.0, 1.0, -2.2, -0.5, 1.0>
    }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "alpha" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.6, 0.05, 0.5>
  texture {
    pigment {
      image_map { png "image_map_alpha.png" map_type 1 interpolate 3 }
      matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.6, 0.05, 0.5>
    }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "negative_sheet" box
box { <-0.4, -0.01, 0.4>, <0.4, 0.01, -0.4>
  matrix <0.9396926207859084, 0.0, 0.3420201433256687, 0.0, 1.0, -0.0, -0.3420201433256687, -0.0, 0.9396926207859084, 1.9, 0.9, -0.2>
  texture {
    pigment { rgbft <0.9, 0.8, 0.6, 0.0, -0.25> }
    finish {
      ambient rgb <0.3, 0.3, 0.3> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

