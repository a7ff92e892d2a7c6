// POV-Ray 3.7 scene written by `prism export pov` from tir.toml; regenerate, do not edit.
// Prism is right-handed, POV-Ray left-handed: points, directions and normals are written as
// (x, y, -z) and transforms as S*M*S with S = diag(1, 1, -1); the image is not mirrored.
// povray-options: +W320 +H180 +A0.2 +AM1 +R2 -J
#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 10
  adc_bailout 0.00392156862745098
  ambient_light rgb <1.0, 1.0, 1.0>
}

background { rgb <0.4, 0.45, 0.55> }

camera {
  perspective
  location <0.0, 0.8, -1.5>
  direction <0.0, -0.17888543819998318, 0.9838699100999074>
  up <0.0, 0.9175721474157137, 0.16683129953012976>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <2.0, 4.0, -0.0>, color rgb <1.0, 1.0, 1.0>
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

// "wall" plane
plane { <0.0, 0.0, -1.0>, -7.0
  texture {
    pigment { rgbft <0.85, 0.85, 0.85, 0.0, 0.0> }
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

// "stripe_a" box
box { <-5.0, -0.6, 6.95>, <5.0, -0.3, 6.9>
  texture {
    pigment { rgbft <0.8, 0.1, 0.1, 0.0, 0.0> }
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

// "stripe_b" box
box { <-5.0, 0.1, 6.95>, <5.0, 0.4, 6.9>
  texture {
    pigment { rgbft <0.1, 0.2, 0.8, 0.0, 0.0> }
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

// "slab" box
box { <-0.6, -0.9, 0.15>, <0.6, 0.6, -0.15>
  matrix <0.6427876096865394, 0.0, 0.766044443118978, 0.0, 1.0, -0.0, -0.766044443118978, -0.0, 0.6427876096865394, -1.4, 0.0, 4.0>
  texture {
    pigment { rgbft <0.97, 1.0, 0.98, 0.92, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.6 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

// "rod" cylinder
cylinder { <0.0, -0.95, 4.3>, <0.2, 0.7, 4.1>, 0.25
  texture {
    pigment { rgbft <1.0, 1.0, 1.0, 0.95, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 2.4 }
}

// "cube" box
box { <-0.4, -0.4, 0.4>, <0.4, 0.4, -0.4>
  matrix <0.7071067811865476, 0.0, 0.7071067811865475, 0.0, 1.0, -0.0, -0.7071067811865475, -0.0, 0.7071067811865476, 1.4, -0.5, 4.2>
  texture {
    pigment { rgbft <0.97, 1.0, 0.98, 0.92, 0.0> }
    finish {
      ambient rgb <0.0, 0.0, 0.0> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.0 brilliance 1.0
      phong 0.6 phong_size 200.0
      specular 0.0 roughness 0.05
      metallic 0.0
      reflection { rgb <0.0, 0.0, 0.0>, rgb <1.0, 1.0, 1.0> falloff 1.0 exponent 1.0 metallic 0.0 fresnel on }
      conserve_energy
    }
  }
  interior { ior 1.5 }
}

