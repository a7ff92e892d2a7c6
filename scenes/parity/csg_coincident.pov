// POV-Ray 3.7 scene written by `prism export pov` from csg_coincident.toml; regenerate, do not edit.
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

background { rgb <0.45, 0.55, 0.7> }

camera {
  perspective
  location <0.0, 2.6, -4.2>
  direction <0.0, -0.5407575913134988, 0.8411784753765535>
  up <0.0, 0.7490335734034836, 0.48152158290223956>
  right <1.0, -0.0, -0.0> * 0.8904573706170724 * image_width / image_height
}

light_source { <3.0, 6.0, -5.0>, color rgb <1.0, 1.0, 1.0>
}

light_source { <-4.0, 3.0, -2.0>, color rgb <0.35, 0.35, 0.4>
}

// "floor" plane
plane { <0.0, 1.0, -0.0>, -1.0
  texture {
    pigment { rgbft <0.7, 0.7, 0.65, 0.0, 0.0> }
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

// "pipe" difference
difference {
  cylinder { <0.0, -0.6, -0.0>, <0.0, 0.6, -0.0>, 0.5
  }
  cylinder { <0.0, -0.6, -0.0>, <0.0, 0.6, -0.0>, 0.3
  }
  matrix <1.0, 0.0, -0.0, 0.0, 0.9063077870366499, -0.42261826174069944, -0.0, 0.42261826174069944, 0.9063077870366499, -2.2, -0.3, -0.0>
  texture {
    pigment { rgbft <0.8, 0.45, 0.2, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "cone_bored" difference
difference {
  cone { <0.0, -0.5, -0.0>, 0.5, <0.0, 0.6, -0.0>, 0.1
  }
  cylinder { <0.0, -0.5, -0.0>, <0.0, 0.2, -0.0>, 0.25
  }
  matrix <0.9659258262890683, 0.25881904510252074, -0.0, -0.2241438680420134, 0.8365163037378079, 0.49999999999999994, 0.12940952255126034, -0.4829629131445341, 0.8660254037844387, -0.8, -0.4, -0.3>
  texture {
    pigment { rgbft <0.3, 0.6, 0.85, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "coaxial" intersection
intersection {
  cylinder { <0.0, -0.5, -0.0>, <0.0, 0.5, -0.0>, 0.4
  }
  cylinder { <0.0, -0.5, -0.0>, <0.0, 0.5, -0.0>, 0.45
  }
  matrix <0.9396926207859084, 0.3420201433256687, -0.0, -0.2801664995932355, 0.7697511313200572, -0.573576436351046, -0.19617469496901108, 0.5389855446957562, 0.8191520442889918, 0.6, -0.3, -0.2>
  texture {
    pigment { rgbft <0.85, 0.8, 0.3, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.4 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
}

// "box_on_plane" intersection
intersection {
  box { <-0.4, -0.4, 0.4>, <0.4, 0.4, -0.4>
  }
  plane { <0.0, 1.0, -0.0>, -0.4
    inverse
  }
  sphere { <0.0, 0.0, -0.0>, 0.55
  }
  matrix <0.8660254037844387, 0.0, 0.49999999999999994, -0.17101007166283433, 0.9396926207859084, 0.29619813272602386, -0.46984631039295416, -0.3420201433256687, 0.8137976813493738, 2.0, -0.2, -0.0>
  texture {
    pigment { rgbft <0.5, 0.8, 0.45, 0.0, 0.0> }
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

// "capped_hemisphere" intersection
intersection {
  sphere { <0.0, 0.0, -0.0>, 0.45
  }
  disc { <0.0, 0.0, -0.0>, <0.0, 1.0, -0.0>, 2.0
  }
  matrix <0.984807753012208, 0.17364817766693033, -0.0, -0.11161889704894966, 0.6330222215594891, 0.766044443118978, 0.133022221559489, -0.7544065067354889, 0.6427876096865394, 0.0, 0.1, -1.4>
  texture {
    pigment { rgbft <0.75, 0.4, 0.7, 0.0, 0.0> }
    finish {
      ambient rgb <0.1, 0.1, 0.1> emission rgb <0.0, 0.0, 0.0>
      diffuse 0.7 brilliance 1.0
      phong 0.5 phong_size 40.0
      specular 0.0 roughness 0.05
      metallic 0.0
    }
  }
  interior { ior 1.0 }
  no_shadow
}

