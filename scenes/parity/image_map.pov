// POV-Ray 3.7 scene written by `prism export pov` from image_map.toml; regenerate, do not edit.
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

background { rgb <0.35, 0.4, 0.5> }

camera {
  perspective
  location <0.0, 1.3, -2.6>
  direction <0.0, -0.1927453040309279, 0.9812488205210874>
  up <0.0, 0.9151276791290855, 0.1797572226860704>
  right <1.0, -0.0, -0.0> * 0.9326153163099972 * image_width / image_height
}

light_source { <-4.0, 6.0, -3.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <5.0, 3.0, -2.0>, color rgb <0.35, 0.35, 0.35>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment {
      image_map { png "image_map.png" map_type 0 }
      matrix <2.8190778623577253, 0.0, 1.0260604299770062, 0.5130302149885031, 9.184850993605148e-17, -1.4095389311788626, -2.094269368838496e-17, 1.0, 5.753957801139251e-17, 0.0, 0.0, -0.0>
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

// "backdrop" plane
plane { <0.0, 0.0, -1.0>, -7.0
  texture {
    pigment {
      image_map { png "image_map.png" map_type 0 interpolate 2 once }
      matrix <6.0, 0.0, -0.0, 0.0, 3.0, -0.0, -0.0, -0.0, 1.0, -2.0, -0.5, -0.0>
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

// "spherical" sphere
sphere { <0.0, 0.0, -0.0>, 0.8
  matrix <0.766044443118978, 0.0, -0.6427876096865393, 0.0, 1.0, -0.0, 0.6427876096865393, -0.0, 0.766044443118978, -1.9, -0.2, 3.2>
  texture {
    pigment {
      image_map { png "image_map.png" map_type 1 interpolate 2 }
      matrix <0.766044443118978, 0.0, -0.6427876096865393, 0.0, 1.0, -0.0, 0.6427876096865393, -0.0, 0.766044443118978, -1.9, -0.2, 3.2>
    }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.3 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "cylindrical" cylinder
cylinder { <0.0, 0.0, -0.0>, <0.0, 1.0, -0.0>, 0.55
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.6, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.0, -1.0, 3.6>
  texture {
    pigment {
      image_map { png "image_map.png" map_type 2 interpolate 4 }
      matrix <0.8660254037844387, 0.0, 0.49999999999999994, 0.0, 1.6, -0.0, -0.49999999999999994, -0.0, 0.8660254037844387, 0.0, -1.0, 3.6>
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

// "alpha" sphere
sphere { <0.0, 0.0, -0.0>, 0.8
  matrix <0.17364817766693041, 0.0, 0.984807753012208, 0.0, 1.0, -0.0, -0.984807753012208, -0.0, 0.17364817766693041, 1.9, -0.2, 3.2>
  texture {
    pigment {
      image_map { png "image_map_alpha.png" map_type 1 interpolate 3 filter all 0.2 transmit all 0.1 }
      matrix <0.17364817766693041, 0.0, 0.984807753012208, 0.0, 1.0, -0.0, -0.984807753012208, -0.0, 0.17364817766693041, 1.9, -0.2, 3.2>
    }
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

// "grey" box
box { <0.0, 0.0, 0.05>, <1.0, 1.0, -0.05>
  matrix <1.2, 0.0, -0.0, 0.0, 0.6, -0.0, -0.0, -0.0, 1.0, -0.6, 1.0, 4.2>
  texture {
    pigment {
      image_map { png "image_map_grey.png" map_type 0 once }
      matrix <1.2, 0.0, -0.0, 0.0, 0.6, -0.0, -0.0, -0.0, 1.0, -0.6, 1.0, 4.2>
    }
    finish {
      ambient rgb <0.4, 0.4, 0.4> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.6 brilliance 1.0
      phong 0.0 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

