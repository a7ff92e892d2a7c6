// POV-Ray 3.7 scene written by `prism export pov` from media_edges.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 +A0.3 +AM1 +R3 -J
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 5
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.35, 0.4, 0.5> }

camera {
  perspective
  location <0.0, 1.6, -1.4>
  direction <0.0, -0.26173297024270464, 0.9651403277699733>
  up <0.0, 1.004840507591521, 0.27249912070278537>
  right <0.9999999999999999, -0.0, -0.0> * 1.0411341011034925 * image_width / image_height
}

light_source { <-1.5, 5.0, 2.5>, color rgb <0.7, 0.7, 0.65>
}

light_source { <2.0, 1.6, 3.4>, color rgb <0.35, 0.42, 0.3>
  area_light <1.6, 0.0, -0.0>, <0.0, 0.0, -1.6>, 3, 3 adaptive 0
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment {
      checker color rgbft <0.85, 0.85, 0.8, 0.0, 0.0>, color rgbft <0.55, 0.6, 0.65, 0.0, 0.0>
      matrix <0.7, 0.0, -0.0, 0.0, 0.7, -0.0, -0.0, -0.0, 0.7, 0.0, 0.0, -0.0>
    }
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

// "clear_with_glass_member" union
union {
  sphere { <0.0, 0.0, -0.0>, 0.8
  }
  box { <-0.45, -0.6, 0.45>, <0.45, 0.1, -0.45>
    texture {
      pigment { rgbft <0.1, 0.15, 0.3, 0.0, 0.0> }
      finish {
        ambient rgb <0.05, 0.05, 0.05> emission rgb <0.0, 0.0, 0.0>
        diffuse 0.3 brilliance 1.0
        phong 0.0 phong_size 40.0
        specular 0.0 roughness 0.05
        metallic 0.0
        reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      }
    }
    interior { ior 1.5 }
    matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.0, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.0, 0.0, -0.0>
  }
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -2.3, -0.2, 4.6>
  texture {
    pigment { rgbft <0.95, 0.97, 1.0, 0.0, 0.92> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.05 brilliance 1.0
      phong 0.4 phong_size 60.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "negative_transmit" sphere
sphere { <0.0, 0.0, -0.0>, 0.45
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, -0.7, -0.3, 3.6>
  texture {
    pigment { rgbft <0.9, 0.6, 0.3, 0.0, -0.6> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.5 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 fade_distance 0.5 fade_power 1001.0 fade_color rgb <0.2, 0.3, 0.9> }
}

// "over_transparent_plate" box
box { <-0.5, -1.0, 0.05>, <0.5, 0.2, -0.05>
  matrix <0.9063077870366499, 0.0, -0.42261826174069944, 0.0, 1.0, -0.0, 0.42261826174069944, -0.0, 0.9063077870366499, 0.6, 0.0, 5.6>
  texture {
    pigment { rgbft <0.9, 0.3, 0.2, 0.8, 0.5> }
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

// "exponent_mirror" sphere
sphere { <0.0, 0.0, -0.0>, 0.5
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 0.9, -0.5, 4.3>
  texture {
    pigment { rgbft <0.3, 0.3, 0.35, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.3 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.7, 0.7, 0.7>, rgb <0.7, 0.7, 0.7> falloff 1.0 exponent 1.6 metallic 0.0 }
    }
  }
  interior { ior 1.0 }
}

// "tinted_pane" box
box { <-0.6, -0.02, 0.6>, <0.6, 0.02, -0.6>
  matrix <1.0, 0.0, -0.0, 0.0, 1.0, -0.0, -0.0, -0.0, 1.0, 1.9, -0.4, 3.4>
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.0, 0.97> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "faceted" superellipsoid
superellipsoid { <0.8, 0.6>
  matrix <0.4505336243589455, 0.0, 0.31546703999307535, 0.0, 0.55, -0.0, -0.31546703999307535, -0.0, 0.4505336243589455, 0.0, 0.3, 6.4>
  texture {
    pigment { rgbft <0.6, 0.8, 0.5, 0.0, 0.0> }
    normal {
      facets 0.6 size 0.3
      matrix <0.4505336243589455, 0.0, 0.31546703999307535, 0.0, 0.55, -0.0, -0.31546703999307535, -0.0, 0.4505336243589455, 0.0, 0.3, 6.4>
      no_bump_scale
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

