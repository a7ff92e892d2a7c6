// POV-Ray 3.7 scene written by `prism export pov` from area_options.toml; regenerate, do not edit.
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
  location <0.0, 1.5, -1.0>
  direction <0.0, -0.3713906763541037, 0.9284766908852593>
  up <0.0, 0.9666687449603696, 0.3866674979841478>
  right <0.9999999999999999, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-2.0, 3.0, 1.5>, color rgb <0.8, 0.8, 0.75>
  area_light <1.5, 0.0, -0.0>, <0.0, 1.5, -0.0>, 9, 9 adaptive 1 circular orient
}

light_source { <2.5, 3.0, 3.0>, color rgb <0.5, 0.5, 0.6>
  spotlight point_at <0.5, -1.0, 4.0> radius 25.0 falloff 35.0 tightness 0.0
  area_light <1.0, 0.0, -0.0>, <0.0, 0.0, -0.8>, 4, 3 adaptive 100
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
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
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.2, -0.5, 3.8>
  texture {
    pigment { rgbft <0.9, 0.5, 0.2, 0.0, 0.0> }
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

// "pillar" cylinder
cylinder { <0.2, -1.0, 4.5>, <0.2, 0.6, 4.5>, 0.25
  texture {
    pigment { rgbft <0.4, 0.8, 0.4, 0.0, 0.0> }
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

// "block" box
box { <1.0, -1.0, 4.0>, <1.8, -0.3, 3.2>
  texture {
    pigment { rgbft <0.4, 0.5, 0.9, 0.0, 0.0> }
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

