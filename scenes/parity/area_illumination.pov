// POV-Ray 3.7 scene written by `prism export pov` from area_illumination.toml; regenerate, do not edit.
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
  location <0.0, 1.3, 0.6>
  direction <0.0, -0.4374657188493062, 0.899235088745796>
  up <0.0, 0.838640416727709, 0.407987229759426>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <-1.3, 0.9, 3.3>, color rgb <1.0, 1.0, 0.95>
  area_light <3.0, 0.0, -0.0>, <0.0, 0.0, -2.0>, 5, 4 adaptive 2 area_illumination on
  fade_distance 1.5 fade_power 1.0
}

light_source { <0.5, 3.0, 2.0>, color rgb <0.5, 0.5, 0.6>
  spotlight point_at <0.0, -1.0, 4.8> radius 15.0 falloff 30.0 tightness 5.0
  area_light <1.2, 0.0, -0.0>, <0.0, 0.0, -1.2>, 4, 4 adaptive 100 circular orient area_illumination on
}

light_source { <1.6, 0.7, 3.6>, color rgb <0.7, 0.7, 0.75>
  area_light <2.0, 0.0, -0.0>, <0.0, 0.0, -1.5>, 5, 4 adaptive 2
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.8, 0.8, 0.8, 0.0, 0.0> }
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

// "glossy ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.7
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -1.3, -0.3, 4.0>
  texture {
    pigment { rgbft <0.9, 0.3, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.8 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.5
    }
  }
  interior { ior 1.0 }
}

// "matte ball" sphere
sphere { <0.0, 0.0, -0.0>, 0.6
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.6, -0.4, 4.2>
  texture {
    pigment { rgbft <0.3, 0.5, 0.9, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.8 brilliance 2.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "pillar" box
box { <-0.3, -1.0, 5.5>, <0.3, 0.8, 4.9>
  texture {
    pigment { rgbft <0.5, 0.8, 0.4, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.4 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

