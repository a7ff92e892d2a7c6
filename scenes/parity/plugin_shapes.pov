// POV-Ray 3.7 scene written by `prism export pov` from plugin_shapes.toml; regenerate, do not edit.
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
  location <0.0, 0.9, 0.5>
  direction <0.0, -0.3231438532915104, 0.9463498560679948>
  up <0.0, 0.7265393486108909, 0.24808660684274322>
  right <1.0, -0.0, -0.0> * 0.7677280700708315 * image_width / image_height
}

light_source { <-2.0, 4.0, -1.0>, color rgb <1.0, 1.0, 1.0>
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

// "ring" torus
torus { 0.5, 0.15
  matrix <0.9396926207859084, 0.0, 0.3420201433256687, 0.2961981327260238, 0.5000000000000001, -0.8137976813493737, -0.17101007166283438, 0.8660254037844386, 0.4698463103929543, -1.8, -0.35, 4.0>
  texture {
    pigment { rgbft <0.9, 0.6, 0.2, 0.0, 0.0> }
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

// "rounded_cube" superellipsoid
superellipsoid { <0.25, 0.25>
  matrix <0.3464101615137755, 0.0, 0.19999999999999998, 0.0, 0.4, -0.0, -0.19999999999999998, -0.0, 0.3464101615137755, -0.6, -0.6, 4.2>
  texture {
    pigment { rgbft <0.3, 0.5, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.5 roughness 0.02
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "star" superellipsoid
superellipsoid { <2.5, 1.5>
  matrix <0.43466662183008076, 0.11646857029613433, -0.0, -7.131643090721471e-18, 2.6615654356020073e-17, -0.45, -0.11646857029613433, 0.43466662183008076, 2.7554552980815448e-17, 0.5, -0.5, 4.5>
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

// "drops" blob
blob {
  threshold 0.6
  sphere { <0.0, 0.0, -0.0>, 0.5, strength 1.0 }
  sphere { <0.45, 0.1, -0.0>, 0.4, strength 1.0 }
  sphere { <0.2, 0.45, -0.1>, 0.35, strength 1.0 }
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.4, -0.7, 4.0>
  texture {
    pigment { rgbft <0.4, 0.8, 0.5, 0.0, 0.0> }
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

// "pill" capsule
merge { cylinder { <0.0, -0.3, -0.0>, <0.0, 0.3, -0.0>, 0.2 open } sphere { <0.0, -0.3, -0.0>, 0.2 } sphere { <0.0, 0.3, -0.0>, 0.2 }
  matrix <0.3420201433256688, 0.9396926207859083, -0.0, -0.9396926207859083, 0.3420201433256688, -0.0, -0.0, -0.0, 1.0, 0.0, -0.2, 5.6>
  texture {
    pigment { rgbft <0.85, 0.35, 0.6, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.7 phong_size 80.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

