// POV-Ray 3.7 scene written by `prism export pov` from csg_normals.toml; regenerate, do not edit.
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
  location <0.0, 1.0, -2.0>
  direction <0.0, -0.19611613513818404, 0.9805806756909202>
  up <0.0, 0.8123396297443052, 0.16246792594886103>
  right <0.9999999999999999, -0.0, -0.0> * 0.8284271247461901 * image_width / image_height
}

light_source { <3.0, 5.0, -3.0>, color rgb <1.0, 1.0, 1.0>
}

// plane
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

// difference
difference {
  box { <-0.8, -0.8, 0.8>, <0.8, 0.8, -0.8>
  }
  sphere { <0.0, 0.0, -0.0>, 0.5
    texture {
      pigment { rgbft <0.4, 0.6, 0.9, 0.0, 0.0> }
      normal {
        ripples 0.8
        frequency 4.0
        matrix <0.3, 0.0, -0.0, 0.0, 0.3, -0.0, -0.0, -0.0, 0.3, 0.0, 0.0, -0.0>
        matrix <0.9396926207859084, -0.17101007166283436, -0.0, 0.3420201433256687, 0.4698463103929542, 0.0, 0.0, -0.0, 1.0, -0.35031181490090624, -0.04266624057974055, 0.6>
      }
      finish {
        ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.6 brilliance 1.0
        phong 0.0 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
      }
    }
    interior { ior 1.0 }
    matrix <0.9396926207859084, 0.3420201433256687, -0.0, -0.6840402866513374, 1.8793852415718169, -0.0, -0.0, -0.0, 1.0, 0.3, 0.2, -0.6>
  }
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.0, 0.0, 3.0>
  texture {
    pigment { rgbft <0.9, 0.8, 0.6, 0.0, 0.0> }
    normal {
      dents 2.0
      matrix <0.2, 0.0, -0.0, 0.0, 0.2, -0.0, -0.0, -0.0, 0.2, 0.0, 0.0, -0.0>
      matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.0, 0.0, 3.0>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.5 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

