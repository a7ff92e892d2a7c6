//! Bad input through the CLI: every broken scene gives a clear message naming the file, line
//! and key, a non-zero exit, no panic, and no output file.

mod common;

use common::failed_run_problems;
use std::path::{Path, PathBuf};
use std::process::Command;

const SPHERE: &str = "[[object]]\nshape = \"sphere\"\n";

struct Case {
    name: &'static str,
    /// The scene text (written to `scene.toml`).
    scene: String,
    /// Extra files (relative path, text) written beside the scene.
    extra: Vec<(&'static str, String)>,
    /// Substrings the error must contain.
    expect: Vec<&'static str>,
    /// Output path override (relative to the case directory unless absolute).
    output: Option<&'static str>,
}

fn case(name: &'static str, scene: &str, expect: &[&'static str]) -> Case {
    Case { name, scene: scene.to_string(), extra: Vec::new(), expect: expect.to_vec(), output: None }
}

fn cases() -> Vec<Case> {
    vec![
        case("syntax error", "[render\nwidth = 10\n", &["scene.toml:1:", "syntax"]),
        case(
            "filter with a POV-Ray method",
            &format!("[render]\nfilter = {{ type = \"gaussian\" }}\nantialias = {{ method = \"pov1\" }}\n{SPHERE}"),
            &["scene.toml:", "render.filter", "stratified"],
        ),
        case(
            "gaussian stddev out of range",
            &format!("[render]\nfilter = {{ type = \"gaussian\", stddev = 0 }}\n{SPHERE}"),
            &["scene.toml:", "render.filter.stddev", "between 0.05 and 4"],
        ),
        case(
            "assumed_gamma of 0",
            &format!("[render]\nassumed_gamma = 0\n{SPHERE}"),
            &["scene.toml:", "render.assumed_gamma", "above 0", "got 0"],
        ),
        case(
            "assumed_gamma neither a number nor srgb",
            &format!("[render]\nassumed_gamma = \"linear\"\n{SPHERE}"),
            &["scene.toml:2:", "render.assumed_gamma", "\"srgb\""],
        ),
        case(
            "unknown filter",
            &format!("[render]\nfilter = {{ type = \"lanczos\" }}\n{SPHERE}"),
            &["scene.toml:2:", "render.filter", "lanczos"],
        ),
        case(
            "view_height on a perspective camera",
            &format!("[camera]\nview_height = 2\n{SPHERE}"),
            &["scene.toml:", "camera.view_height", "orthographic"],
        ),
        case(
            "orthographic camera with a lens",
            &format!("[camera]\nprojection = \"orthographic\"\naperture = 0.1\n{SPHERE}"),
            &["scene.toml:", "camera.aperture", "no lens"],
        ),
        case(
            "adaptive focal blur without a lens",
            &format!("[camera]\nblur_variance = 0.001\n{SPHERE}"),
            &["scene.toml:2:1", "camera.blur_variance", "no aperture"],
        ),
        case(
            "blur_variance out of POV-Ray's range",
            &format!("[camera]\naperture = 0.1\nblur_variance = 2\n{SPHERE}"),
            &["scene.toml:3:1", "camera.blur_variance", "between 0 and 1"],
        ),
        case(
            "blur_min_samples above samples",
            &format!(
                "[render]\nsamples = 8\n[camera]\naperture = 0.1\nblur_variance = 0.001\nblur_min_samples = 9\n{SPHERE}"
            ),
            &["scene.toml:6:1", "camera.blur_min_samples", "between 1 and [render] samples (8)"],
        ),
        case(
            "adaptive focal blur beside adaptive sampling",
            &format!("[render]\nsamples = 16\nnoise = 0.01\n[camera]\naperture = 0.1\nblur_variance = 0.001\n{SPHERE}"),
            &["scene.toml:6:1", "camera.blur_variance", "use one"],
        ),
        case(
            "blur_confidence without blur_variance",
            &format!("[camera]\naperture = 0.1\nblur_confidence = 0.5\n{SPHERE}"),
            &["scene.toml:3:1", "camera.blur_confidence", "without blur_variance"],
        ),
        case(
            "pigment with an empty color_map",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\ncolor_map = []\n",
            &["scene.toml:5:", "object[0].material.pigment.color_map", "at least one entry"],
        ),
        case(
            "unknown pigment pattern",
            "[[object]]\nshape = \"sphere\"\nmaterial = { pigment = { pattern = \"chekcer\" } }\n",
            &["scene.toml:3:", "object[0].material.pigment.pattern", "did you mean `checker`"],
        ),
        case(
            "unknown pigment key",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\nfrequncy = 2\n",
            &["scene.toml:5:", "object[0].material.pigment.frequncy", "did you mean `frequency`"],
        ),
        case(
            "color_map out of order",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\ncolor_map = [[0.6, [1, 1, 1]], [0.2, [0, 0, 0]]]\n",
            &["scene.toml:5:", "object[0].material.pigment.color_map", "entry 1", "ascending"],
        ),
        case(
            "unknown normal pattern",
            "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"bumsp\" } }\n",
            &["scene.toml:3:", "object[0].material.normal.pattern", "did you mean `bumps`"],
        ),
        case(
            "unknown normal key",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\nbumpsize = 2\n",
            &["scene.toml:5:", "object[0].material.normal.bumpsize", "did you mean `bump_size`"],
        ),
        case(
            "non-finite bump_size",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\nbump_size = nan\n",
            &["scene.toml:5:", "object[0].material.normal.bump_size", "finite"],
        ),
        case(
            "frequency on bumps",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\nfrequency = 2\n",
            &["scene.toml:5:", "object[0].material.normal.frequency", "ripples and waves"],
        ),
        case(
            "crackle metric out of range",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"crackle\"\nmetric = 0\ncolor_map = [[0, [1, 1, 1]]]\n",
            &["scene.toml:5:", "object[0].material.pigment.metric", "above 0 and at most 100"],
        ),
        case(
            "negative crackle offset",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"crackle\"\noffset = -0.5\ncolor_map = [[0, [1, 1, 1]]]\n",
            &["scene.toml:5:", "object[0].material.pigment.offset", "not negative"],
        ),
        case(
            "crackle form on another pattern",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"granite\"\nform = [1, 0, 0]\ncolor_map = [[0, [1, 1, 1]]]\n",
            &["scene.toml:5:", "object[0].material.pigment.form", "belongs to crackle"],
        ),
        case(
            "misspelt crackle key",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"crackle\"\nmetrik = 1\n",
            &["scene.toml:5:", "object[0].material.pigment.metrik", "did you mean `metric`"],
        ),
        case(
            "normal accuracy out of range",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"granite\"\naccuracy = 0\n",
            &["scene.toml:5:", "object[0].material.normal.accuracy", "at least 1e-6"],
        ),
        case(
            "accuracy on a normal-only pattern",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\naccuracy = 0.01\n",
            &["scene.toml:5:", "object[0].material.normal.accuracy", "pigment patterns"],
        ),
        case(
            "crackle normal metric out of range",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"crackle\"\nmetric = 1000\n",
            &["scene.toml:5:", "object[0].material.normal.metric", "at most 100"],
        ),
        case(
            "facets of size 0",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"facets\"\nsize = 0\n",
            &["scene.toml:5:", "object[0].material.normal.size", "above 0"],
        ),
        case(
            "a discrete normal with a short list of normals",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"hexagon\"\nnormals = [{ pattern = \"bumps\" }, { pattern = \"dents\" }]\n",
            &["scene.toml:5:", "object[0].material.normal.normals", "takes 3 normals"],
        ),
        case(
            "a bad normal in a discrete pattern's list",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"checker\"\nnormals = [{ pattern = \"bumps\" }, { pattern = \"dents\", scale = 0 }]\n",
            &["scene.toml:5:", "object[0].material.normal.normals[1].scale", "scale"],
        ),
        case(
            "no_bump_scale that is not a boolean",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\nno_bump_scale = 1\n",
            &["scene.toml:5:", "no_bump_scale"],
        ),
        case(
            "normal with an empty normal_map",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bozo\"\nnormal_map = []\n",
            &["scene.toml:5:", "object[0].material.normal.normal_map", "at least one"],
        ),
        case(
            "slope_map value not finite",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"granite\"\n\
             slope_map = [[0, [0, 1]], [nan, [1, 0]]]\n",
            &["scene.toml:5:", "object[0].material.normal.slope_map", "entry 1", "not a finite number"],
        ),
        case(
            "slope_map on a normal-only pattern",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bumps\"\nslope_map = [[0, [0, 1]]]\n",
            &["scene.toml:5:", "object[0].material.normal.slope_map", "pigment patterns"],
        ),
        case(
            "a broken normal_map entry",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bozo\"\nnormal_map = [\n  \
             [0, { pattern = \"bumps\" }],\n  [1, { pattern = \"ripples\", frequency = inf }],\n]\n",
            &["scene.toml:7:", "object[0].material.normal.normal_map[1][1].frequency", "finite"],
        ),
        case(
            "unknown key in a normal_map entry",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"bozo\"\n\
             normal_map = [[0, { pattern = \"bumps\", bumpsize = 1 }]]\n",
            &["scene.toml:5:", "bumpsize", "did you mean `bump_size`"],
        ),
        case(
            "average without a map",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"average\"\n",
            &["scene.toml:3:", "object[0].material.pigment.pigment_map", "`average` needs"],
        ),
        case(
            "average normal with a negative weight",
            "[[object]]\nshape = \"sphere\"\n[object.material.normal]\npattern = \"average\"\n\
             normal_map = [[1, { pattern = \"bumps\" }], [-2, { pattern = \"dents\" }]]\n",
            &["scene.toml:5:", "object[0].material.normal.normal_map", "entry 1", "not negative"],
        ),
        case(
            "average pigment with weights adding up to 0",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"average\"\n\
             pigment_map = [[0, { color = [1, 1, 1] }]]\n",
            &["scene.toml:5:", "object[0].material.pigment.pigment_map", "above 0"],
        ),
        case(
            "unknown pattern near average",
            "[[object]]\nshape = \"sphere\"\nmaterial = { normal = { pattern = \"averag\" } }\n",
            &["scene.toml:3:", "object[0].material.normal.pattern", "did you mean `average`"],
        ),
        case(
            "pigment with an empty pigment_map",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\npigment_map = []\n",
            &["scene.toml:5:", "object[0].material.pigment.pigment_map", "at least one"],
        ),
        case(
            "pigment_map values out of order",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\n\
             pigment_map = [[0.6, { color = [1, 1, 1] }], [0.2, { color = [0, 0, 0] }]]\n",
            &["scene.toml:5:", "object[0].material.pigment.pigment_map", "entry 1", "ascending"],
        ),
        case(
            "pigment_map on a discrete pattern",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"checker\"\n\
             colors = [[1, 1, 1], [0, 0, 0]]\npigment_map = [[0, { color = [1, 1, 1] }]]\n",
            &["scene.toml:6:", "object[0].material.pigment.pigment_map", "takes `colors`"],
        ),
        case(
            "a discrete pattern with too few pigments",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"hexagon\"\n\
             pigments = [{ color = [1, 1, 1] }, { color = [0, 0, 0] }]\n",
            &["scene.toml:5:", "object[0].material.pigment.pigments", "takes 3 pigments"],
        ),
        case(
            "color_map and pigment_map",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\n\
             color_map = [[0, [1, 1, 1]]]\npigment_map = [[0, { color = [1, 1, 1] }]]\n",
            &["scene.toml:6:", "object[0].material.pigment.pigment_map", "not both"],
        ),
        case(
            "a broken pigment_map entry",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\npigment_map = [\n  \
             [0, { color = [1, 1, 1] }],\n  [1, { pattern = \"onion\", color_map = [[2, [0, 0, 0]], [1, [1, 1, 1]]] }],\n]\n",
            &["scene.toml:7:", "object[0].material.pigment.pigment_map[1].color_map", "ascending"],
        ),
        case(
            "unknown key in a pigment_map entry",
            "[[object]]\nshape = \"sphere\"\n[object.material.pigment]\npattern = \"onion\"\n\
             pigment_map = [[0, { pattern = \"onion\", colour_map = [] }]]\n",
            &["scene.toml:5:", "colour_map", "did you mean `color_map`"],
        ),
        case(
            "a plain colour as a material's pigment",
            "[[object]]\nshape = \"sphere\"\nmaterial = { pigment = { color = [1, 0, 0] } }\n",
            &["scene.toml:3:", "object[0].material.pigment.color", "`pigment_map` entry"],
        ),
        case(
            "color beside a pigment",
            "[[object]]\nshape = \"sphere\"\n[object.material]\ncolor = [1, 0, 0]\npigment = { pattern = \"checker\", colors = [[1, 1, 1], [0, 0, 0]] }\n",
            &["scene.toml:4:", "object[0].material.color", "beside `pigment`"],
        ),
        case(
            "unknown top-level key",
            "[rendr]\nwidth = 10\n",
            &["scene.toml:1:", "unknown top-level key `rendr`", "did you mean `render`"],
        ),
        case(
            "unknown render key",
            "[render]\nwidht = 10\n",
            &["scene.toml:2:1", "render.widht", "did you mean `width`"],
        ),
        case("wrong type", "[render]\nwidth = \"big\"\n", &["scene.toml:2:", "render.width", "invalid type"]),
        case(
            "unknown shape",
            "[[object]]\nshape = \"sphear\"\n",
            &["scene.toml:2:", "unknown shape `sphear`", "did you mean `sphere`"],
        ),
        case(
            "negative radius",
            "[[object]]\nshape = \"sphere\"\nradius = -1\n",
            &["scene.toml:3:", "object[0].radius", "greater than 0"],
        ),
        case(
            "zero-length normal",
            "[[object]]\nshape = \"plane\"\nnormal = [0, 0, 0]\n",
            &["scene.toml:3:", "object[0].normal"],
        ),
        case(
            "NaN translate",
            &format!("{SPHERE}transform = {{ translate = [nan, 0, 0] }}\n"),
            &["scene.toml:3:", "object[0].transform", "not finite"],
        ),
        case(
            "missing include",
            "include = [\"nowhere.toml\"]\n",
            &["scene.toml:1:", "cannot read included file", "nowhere.toml"],
        ),
        Case {
            extra: vec![("b.toml", "include = [\"scene.toml\"]\n".into())],
            ..case("include cycle", "include = [\"b.toml\"]\n", &["include cycle", "b.toml", "scene.toml"])
        },
        Case {
            output: Some("/nonexistent-dir/out.png"),
            ..case("unwritable output", SPHERE, &["/nonexistent-dir/out.png", "cannot write"])
        },
        Case { output: Some("out.xyz"), ..case("unknown output format", SPHERE, &["out.xyz", "unknown image format"]) },
        case("zero width", "[render]\nwidth = 0\n", &["scene.toml:2:1:", "width must be between 1 and"]),
        case("absurd size", "[render]\nwidth = 60000\nheight = 60000\n", &["scene.toml:", "exceeds the limit"]),
        case("zero samples", "[render]\nsamples = 0\n", &["scene.toml:", "samples must be between"]),
        case("negative width", "[render]\nwidth = -5\n", &["scene.toml:2:", "render.width"]),
        case(
            "unknown material",
            &format!("{SPHERE}material = \"chrom\"\n[materials.chrome]\nreflection = 1\n"),
            &["scene.toml:3:", "no material is named `chrom`", "did you mean `chrome`"],
        ),
        case(
            "unknown material key",
            "[materials.red]\ncolr = [1, 0, 0]\n",
            &["scene.toml:2:1", "materials.red.colr", "did you mean `color`"],
        ),
        case(
            "bad reflection key",
            "[materials.m]\nreflection = { mni = 0.1 }\n",
            &["scene.toml:2:", "materials.m.reflection", "mni"],
        ),
        case(
            "camera looks at itself",
            "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, 0]\n",
            &["scene.toml:3:1", "camera.look_at", "look_at is the camera position"],
        ),
        case(
            "spot aimed at its own position",
            "[[light]]\nkind = \"spot\"\nposition = [0, 1, 0]\npoint_at = [0, 1, 0]\n",
            &["scene.toml:4:1", "light[0].point_at", "no direction"],
        ),
        case(
            "negative light under path",
            &format!("[render]\nintegrator = \"path\"\n{SPHERE}\n[[light]]\nposition = [0, 5, 0]\nintensity = -2\n"),
            &["light[0].intensity", "cannot be negative", "classic"],
        ),
        case(
            "negative light colour under path",
            &format!("[render]\nintegrator = \"path\"\n{SPHERE}\n[[light]]\ncolor = [1, -1, 1]\n"),
            &["light[0].color", "cannot be negative"],
        ),
        case(
            "enormous light intensity",
            "[[light]]\nintensity = 1e300\n",
            &["scene.toml:2:1", "light[0].intensity", "got 1e300"],
        ),
        case(
            "unknown light kind",
            "[[light]]\nkind = \"laser\"\n",
            &["scene.toml:2:", "light[0].kind", "unknown variant"],
        ),
        case(
            "key for another light kind",
            "[[light]]\nkind = \"point\"\nradius = 10\n",
            &["scene.toml:3:1", "does not apply to a point light", "`radius` belongs to kind = \"spot\" or \"area\""],
        ),
        case("missing shape", "[[object]]\nradius = 1\n", &["scene.toml:1:", "missing key `shape`", "known shapes"]),
        case(
            "duplicate name",
            &format!("{SPHERE}name = \"a\"\n{SPHERE}name = \"a\"\n"),
            &["scene.toml:6:", "duplicate object name `a`"],
        ),
        case(
            "unknown parent",
            &format!("{SPHERE}name = \"body\"\n{SPHERE}parent = \"bdy\"\n"),
            &["scene.toml:6:", "no object is named `bdy`", "did you mean `body`"],
        ),
        case(
            "parent cycle",
            &format!("{SPHERE}name = \"a\"\nparent = \"b\"\n{SPHERE}name = \"b\"\nparent = \"a\"\n"),
            &["scene.toml:", "parent chain forms a cycle"],
        ),
        case(
            "singular transform",
            &format!("{SPHERE}transform = {{ scale = [1, 0, 1] }}\n"),
            &["scene.toml:3:", "object[0].transform", "singular"],
        ),
        case(
            "matrix with translate",
            &format!(
                "{SPHERE}transform = {{ translate = [1, 0, 0], matrix = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]] }}\n"
            ),
            &["scene.toml:3:", "cannot be combined"],
        ),
        case(
            "degenerate cone",
            "[[object]]\nshape = \"cone\"\nbase = [0, 0, 0]\napex = [0, 0, 0]\n",
            &["scene.toml:4:", "object[0].apex"],
        ),
        case(
            "unknown shape parameter",
            "[[object]]\nshape = \"sphere\"\nradus = 2\n",
            &["scene.toml:3:1", "unknown key `radus`", "did you mean `radius`"],
        ),
        case("objects not an array", "object = 5\n", &["scene.toml:1:", "must be an array of tables"]),
        case(
            "CSG group without members",
            "[[object]]\nshape = \"union\"\nmembers = []\n",
            &["scene.toml:3:", "object[0].members", "`union` has no members"],
        ),
        case(
            "CSG group without a members key",
            "[[object]]\nshape = \"merge\"\n",
            &["scene.toml:1:", "object[0]", "`merge` needs `members`"],
        ),
        case(
            "difference with one member",
            "[[object]]\nshape = \"difference\"\nmembers = [{ shape = \"sphere\" }]\n",
            &["scene.toml:3:", "object[0].members", "at least 2 members (it has 1)"],
        ),
        case(
            "unknown key in a CSG member",
            "[[object]]\nshape = \"intersection\"\nmembers = [\n  { shape = \"sphere\" },\n  { shape = \"box\", inverted = true },\n]\n",
            &[
                "scene.toml:5:",
                "object[0].members[1].inverted",
                "unknown key `inverted` for shape `box`",
                "did you mean `inverse`",
            ],
        ),
        case(
            "unknown key on a CSG group",
            "[[object]]\nshape = \"union\"\nmember = []\n",
            &["scene.toml:3:", "unknown key `member` for `union`", "did you mean `members`"],
        ),
        case(
            "missing mesh file in a CSG group",
            "[[object]]\nshape = \"union\"\nmembers = [{ shape = \"mesh\", file = \"a.obj\" }]\n",
            &["scene.toml:3:", "object[0].members[0].file", "cannot import mesh", "a.obj"],
        ),
        case(
            "mesh keys a CSG member cannot take",
            "[[object]]\nshape = \"union\"\nmembers = [{ shape = \"mesh\", file = \"a.obj\", import_lights = true, smoth_angle = 30 }]\n",
            &[
                "scene.toml:3:",
                "object[0].members[0].import_lights",
                "cannot be set on a mesh in a CSG group",
                "object[0].members[0].smoth_angle",
                "did you mean `smooth_angle`",
            ],
        ),
        case(
            "nested CSG member with a bad radius",
            "[[object]]\nshape = \"union\"\nmembers = [{ shape = \"difference\", members = [\n  { shape = \"sphere\" },\n  { shape = \"sphere\", radius = -1 },\n] }]\n",
            &["scene.toml:5:", "object[0].members[0].members[1].radius", "greater than 0"],
        ),
        case(
            "unknown CSG operation",
            "[[object]]\nshape = \"unoin\"\n",
            &["scene.toml:2:", "unknown shape `unoin`", "did you mean `union`"],
        ),
        case(
            "CSG member material unknown",
            "[[object]]\nshape = \"union\"\nmembers = [{ shape = \"sphere\", material = \"glas\" }]\n[materials.glass]\ncolor = [1, 1, 1]\n",
            &["scene.toml:3:", "object[0].members[0].material", "no material is named `glas`", "did you mean `glass`"],
        ),
        case(
            "name on a CSG member",
            "[[object]]\nshape = \"union\"\nmembers = [{ shape = \"sphere\", name = \"a\" }]\n",
            &["scene.toml:3:", "object[0].members[0].name", "cannot be set on a CSG member"],
        ),
        case(
            "empty layers",
            "[[object]]\nshape = \"sphere\"\nmaterial = { layers = [] }\n",
            &["scene.toml:3:", "object[0].material.layers", "at least one layer"],
        ),
        case(
            "a layer key beside layers",
            "[[object]]\nshape = \"sphere\"\n[object.material]\nphong = 0.5\n[[object.material.layers]]\ncolor = [1, 0, 0]\n",
            &["scene.toml:4:", "object[0].material.phong", "belongs to a layer"],
        ),
        case(
            "a bsdf layer",
            "[materials.m]\n[[materials.m.layers]]\ncolor = [1, 0, 0]\n[[materials.m.layers]]\nbsdf = { type = \"diffuse\" }\n[[object]]\nshape = \"sphere\"\nmaterial = \"m\"\n",
            &["scene.toml:5:", "materials.m.layers[1].bsdf", "no layered form"],
        ),
        case(
            "a pbr layer",
            "[[object]]\nshape = \"sphere\"\nmaterial = { layers = [{ pbr = { metallic = 1 } }] }\n",
            &["scene.toml:3:", "object[0].material.layers[0].pbr", "no layered form"],
        ),
        case(
            "an interior key in a layer",
            "[[object]]\nshape = \"sphere\"\nmaterial = { layers = [{ transmit = 1 }, { ior = 1.5 }] }\n",
            &["scene.toml:3:", "object[0].material.layers[1].ior", "beside `layers`"],
        ),
        case(
            "a bad value in a layer",
            "[[object]]\nshape = \"sphere\"\n[[object.material.layers]]\nroughness = 0\n",
            &["scene.toml:4:", "object[0].material.layers[0].roughness", "greater than 0"],
        ),
        case("infinite light", "[[light]]\nposition = [inf, 0, 0]\n", &["scene.toml:", "position", "finite"]),
        case(
            "shadowless spot",
            &format!("[[light]]\nkind = \"spot\"\nposition = [0, 5, 0]\nshadowless = true\n{SPHERE}"),
            &["scene.toml:4:", "light[0].shadowless", "`spotlight shadowless`", "kind = \"point\""],
        ),
        case(
            "shadowless area spot",
            &format!("[[light]]\nkind = \"area\"\nspot = true\nposition = [0, 5, 0]\nshadowless = true\n{SPHERE}"),
            &["scene.toml:5:", "light[0].shadowless", "a spot light cannot be shadowless"],
        ),
        ply_case(
            "PLY face past the vertex list",
            &format!("{PLY_HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
            &["bad.ply:13", "element `face` item 0", "vertex index 7", "only 3 vertices"],
        ),
        ply_case(
            "PLY without end_header",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
            &["bad.ply", "no `end_header`"],
        ),
        ply_case(
            "PLY count larger than the data",
            &PLY_HEADER.replace("vertex 3", "vertex 4000000000"),
            &["bad.ply:3", "`vertex`", "4000000000 items"],
        ),
        ply_case(
            "PLY unknown property type",
            &PLY_HEADER.replace("float y", "vec3 y"),
            &["bad.ply:5", "unknown property type `vec3`"],
        ),
        ply_case(
            "PLY truncated data",
            &format!("{PLY_HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
            &["bad.ply:13", "element `face` item 0", "ends here"],
        ),
        ply_case(
            "PLY data shorter than its counts",
            &format!("{PLY_HEADER}0 0 0\n1 0 0\n"),
            &["bad.ply:3", "element `vertex`", "cannot hold them"],
        ),
        case(
            "missing font",
            "[[object]]\nshape = \"text\"\nfont = \"nope.ttf\"\nstring = \"a\"\n",
            &["scene.toml:3:", "font", "nope.ttf"],
        ),
        Case {
            extra: vec![("bad.ttf", "not a font".into())],
            ..case(
                "a font that is not one",
                "[[object]]\nshape = \"text\"\nfont = \"bad.ttf\"\nstring = \"a\"\n",
                &["scene.toml:3:", "bad.ttf", "not a readable TrueType font"],
            )
        },
        case("character without a glyph", &text_scene("string = \"a\\U0010FFFF\""), &["scene.toml:4:", "U+10FFFF"]),
        case("text thickness NaN", &text_scene("thickness = nan"), &["scene.toml:4:", "thickness", "greater than 0"]),
        case("text offset of one number", &text_scene("offset = [1.0]"), &["scene.toml:4:", "offset", "[x, y]"]),
        ply_case(
            "PLY count smaller than the data",
            &format!("{}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", PLY_HEADER.replace("face 1", "face 0")),
            &["bad.ply:13", "data after the last element"],
        ),
    ]
}

/// A text object with the shipped font and `line` as its last key (line 4; the string is "a"
/// unless `line` sets it).
fn text_scene(line: &str) -> String {
    let font = format!("{}/assets/fonts/DejaVuSans.ttf", env!("CARGO_MANIFEST_DIR"));
    let string = if line.starts_with("string") { String::new() } else { "string = \"a\"\n".into() };
    format!("[[object]]\nshape = \"text\"\nfont = \"{font}\"\n{line}\n{string}")
}

/// An ASCII PLY header: three vertices, one face.
const PLY_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

/// A scene importing `bad.ply` with the text `ply`.
fn ply_case(name: &'static str, ply: &str, expect: &[&'static str]) -> Case {
    let mut expect = expect.to_vec();
    expect.push("scene.toml:3:");
    Case {
        extra: vec![("bad.ply", ply.to_string())],
        ..case(name, "[[object]]\nshape = \"mesh\"\nfile = \"bad.ply\"\n", &expect)
    }
}

fn prism() -> Command {
    Command::new(env!("CARGO_BIN_EXE_prism"))
}

fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    v.sort();
    v
}

#[test]
fn broken_scenes_fail_clearly_without_output() {
    let all = cases();
    assert!(all.len() >= 20);
    let root = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    for (i, c) in all.iter().enumerate() {
        let dir = root.path().join(format!("case{i}"));
        std::fs::create_dir(&dir).unwrap();
        std::fs::write(dir.join("scene.toml"), &c.scene).unwrap();
        for (name, text) in &c.extra {
            std::fs::write(dir.join(name), text).unwrap();
        }
        let before = files_in(&dir);
        let output = c.output.map_or_else(|| dir.join("out.png"), |o| dir.join(o));
        let run = prism()
            .current_dir(&dir)
            .args(["render", "scene.toml", "-o"])
            .arg(&output)
            .args(["--exr"])
            .arg(dir.join("out.exr"))
            .args(["--width", "8", "--height", "6"].iter().filter(|_| !c.scene.contains("width")))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        let mut problems = failed_run_problems(&run, &c.expect);
        if files_in(&dir) != before {
            problems.push(format!("files changed: {:?}", files_in(&dir)));
        }
        if !problems.is_empty() {
            failures.push(format!("{}: {}\n--- stderr:\n{stderr}", c.name, problems.join("; ")));
        }
    }
    assert!(failures.is_empty(), "{} of {} cases failed:\n{}", failures.len(), all.len(), failures.join("\n"));
}

/// A glTF quad (mesh 0: its triangles, then its corners again as points) and a point light
/// with a `range` on node 1.
const LAMP_GLTF: &str = r#"{
  "asset": { "version": "2.0" },
  "scene": 0,
  "scenes": [{ "nodes": [0, 1] }],
  "nodes": [
    { "mesh": 0 },
    { "translation": [0, 2, 0], "extensions": { "KHR_lights_punctual": { "light": 0 } } }
  ],
  "meshes": [{ "primitives": [
    { "attributes": { "POSITION": 1 }, "indices": 0 },
    { "attributes": { "POSITION": 1 }, "mode": 0 }
  ] }],
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": { "KHR_lights_punctual": { "lights": [{ "type": "point", "intensity": 20, "range": 10 }] } },
  "buffers": [{ "byteLength": 60, "uri": "data:application/octet-stream;base64,AAABAAIAAAACAAMAAAAAwAAAAAAAAADAAAAAwAAAAAAAAABAAAAAQAAAAAAAAABAAAAAQAAAAAAAAADA" }],
  "bufferViews": [
    { "buffer": 0, "byteOffset": 0, "byteLength": 12 },
    { "buffer": 0, "byteOffset": 12, "byteLength": 48 }
  ],
  "accessors": [
    { "bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR" },
    { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 0, -2], "max": [2, 0, 2] }
  ]
}"#;

#[test]
fn warnings_name_the_place_and_the_render_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lamp.gltf"), LAMP_GLTF).unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n\n[[object]]\nshape = \"mesh\"\nfile = \"lamp.gltf\"\n\
                 import_lights = true\ntransform = { translate = [0, -1, -3] }\n\n\
                 [[object]]\nshape = \"mesh\"\nfile = \"lamp.gltf\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(dir.path().join("out.png").is_file(), "{stderr}");
    // The imported light's `range`, at the key that imports it.
    let range = "scene.toml:8:17: warning in `object[0].import_lights`: lamp.gltf: light 0: `range` 10 is ignored";
    assert!(stderr.contains(range), "{stderr}");
    // What the file skips, at the first object naming it, and only there.
    let points = "scene.toml:7:8: warning in `object[0].file`: lamp.gltf: mesh 0 primitive 1: Points primitives \
                  are not rendered; skipped";
    assert!(stderr.contains(points), "{stderr}");
    assert_eq!(stderr.matches("Points primitives").count(), 1, "{stderr}");
    assert!(stderr.contains("rendered 8x6"), "{stderr}");
}

#[test]
fn assumed_gamma_below_one_or_under_path_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let render = |keys: &str| {
        std::fs::write(dir.path().join("scene.toml"), format!("[render]\nwidth = 4\nheight = 3\n{keys}\n{SPHERE}"))
            .unwrap();
        let run = prism().current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png"]).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr).to_string();
        assert!(run.status.success(), "{stderr}");
        stderr
    };
    let low = render("assumed_gamma = 0.45");
    assert!(low.contains("warning in `render.assumed_gamma`") && low.contains("did you mean 2.2"), "{low}");
    let path = render("assumed_gamma = 2.2\nintegrator = \"path\"");
    assert!(path.contains("warning in `render.assumed_gamma`") && path.contains("classic integrator"), "{path}");
    assert!(!render("assumed_gamma = 2.2").contains("warning"));
}

/// An open mesh in a CSG group is a warning naming its open edges: it renders as POV-Ray
/// renders a mesh without `inside_vector`, a surface inside nothing.
#[test]
fn an_open_mesh_in_a_csg_group_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    // A tetrahedron without its base: three open edges.
    std::fs::write(dir.path().join("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        .unwrap();
    let scene = "[render]\nwidth = 4\nheight = 3\n[[object]]\nshape = \"union\"\nmembers = [{ shape = \"sphere\" },\n  { shape = \"mesh\", file = \"open.obj\" }]\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let stderr = render_successfully(dir.path(), &[]);
    assert!(
        stderr.contains("scene.toml:7:")
            && stderr.contains("warning in `object[0].members[1].file`")
            && stderr.contains("not a closed surface (3 edges border a single triangle)"),
        "{stderr}"
    );
}

/// Renders `scene.toml` in `dir` with `args`, which must succeed; its standard error.
fn render_successfully(dir: &Path, args: &[&str]) -> String {
    let run = prism().current_dir(dir).args(["render", "scene.toml", "-o", "out.png"]).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr).to_string();
    assert!(run.status.success(), "{stderr}");
    stderr
}

/// A half-float EXR saturates values beyond half's range with a warning that counts them;
/// a float EXR keeps them, and an image without a half-float EXR warns of nothing.
#[test]
fn values_beyond_half_are_counted_in_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n[world]\nbackground = [100000.0, 0.5, 0.5]\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let render = |args: &[&str]| render_successfully(dir.path(), args);
    let half = render(&["--exr", "half.exr", "--half"]);
    assert!(half.contains("warning: --half: 48 values exceed the largest half float (65504)"), "{half}");
    let back = prism::output::read_exr(&dir.path().join("half.exr")).unwrap();
    assert!(back.pixels.iter().all(|p| p[0] == 65504.0), "{:?}", back.pixels[0]);
    assert!(!render(&["--exr", "float.exr"]).contains("warning"));
    let back = prism::output::read_exr(&dir.path().join("float.exr")).unwrap();
    assert!(back.pixels.iter().all(|p| p[0] == 100000.0), "{:?}", back.pixels[0]);
    assert!(!render(&["--half"]).contains("warning"));
}

/// `[world] environment` is the path integrator's: under classic it is ignored with a
/// warning naming the key (the image shows `background`), under path it lights the scene.
#[test]
fn an_environment_map_under_classic_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let map = common::repo().join("assets/env/sunset_256x128.exr");
    std::fs::copy(&map, dir.path().join("sky.exr")).unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n[world]\nenvironment = { file = \"sky.exr\" }\n\
                 [[light]]\nposition = [0, 5, 5]\n[[object]]\nshape = \"sphere\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let render = |args: &[&str]| render_successfully(dir.path(), args);
    let classic = render(&[]);
    assert!(
        classic.contains("warning in `world.environment`") && classic.contains("path integrator only"),
        "{classic}"
    );
    assert!(!render(&["--integrator", "path", "--samples", "1"]).contains("world.environment"));
}

/// A negative `emission` darkens under classic (POV-Ray's reading, no warning) and emits
/// nothing under path, with a warning at the key.
#[test]
fn negative_emission_under_path_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n[[light]]\nposition = [0, 5, 5]\n\
                 [[object]]\nshape = \"sphere\"\nmaterial = { emission = [-0.5, 0.2, 0.2] }\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let render = |args: &[&str]| render_successfully(dir.path(), args);
    let path = render(&["--integrator", "path", "--samples", "1"]);
    assert!(path.contains("scene.toml:6:1: warning in `object[0].material.emission`"), "{path}");
    assert!(!render(&[]).contains("warning"));
}

#[test]
fn a_spot_radius_beyond_its_falloff_is_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n[[light]]\nkind = \"spot\"\nposition = [0, 5, 0]\n\
                 radius = 40\nfalloff = 20\n[[object]]\nshape = \"sphere\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success() && dir.path().join("out.png").is_file(), "{stderr}");
    assert!(stderr.contains("scene.toml:7:1: warning in `light[0].radius`: radius 40 exceeds falloff 20"), "{stderr}");
    // Equal angles are a hard edge as written: no warning.
    std::fs::write(dir.path().join("equal.toml"), scene.replace("radius = 40", "radius = 20")).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "equal.toml", "-o", "out.png"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success() && !stderr.contains("exceeds falloff"), "{stderr}");
}

/// POV-Ray's adaptive focal blur keys are classic's: under `path` (here through
/// `--integrator`) they are ignored with a warning at the key, so the scene still renders;
/// `--samples` below `blur_min_samples` lowers the minimum with it.
#[test]
fn adaptive_blur_keys_bend_to_command_line_overrides() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\nsamples = 16\n[camera]\naperture = 0.1\nblur_variance = 0.001\n\
                 blur_min_samples = 7\n[[light]]\nposition = [0, 5, 5]\n[[object]]\nshape = \"sphere\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let run = |args: &[&str]| {
        let run = prism().current_dir(dir.path()).args(["render", "scene.toml", "-o", "out.png"]).args(args).output();
        let run = run.unwrap();
        (run.status.success(), String::from_utf8_lossy(&run.stderr).into_owned())
    };
    let (ok, stderr) = run(&["--integrator", "path"]);
    assert!(
        ok && stderr.contains("scene.toml:7:1: warning in `camera.blur_variance`: blur_variance is ignored"),
        "{stderr}"
    );
    let (ok, stderr) = run(&[]);
    assert!(ok && !stderr.contains("warning"), "{stderr}");
    let (ok, stderr) = run(&["--samples", "1"]);
    assert!(ok && stderr.contains("at 1 spp"), "{stderr}");
}

#[test]
fn a_path_traced_scene_without_light_renders_black_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let dark = "[render]\nwidth = 8\nheight = 6\nintegrator = \"path\"\n[[object]]\nshape = \"sphere\"\n";
    std::fs::write(dir.path().join("dark.toml"), dark).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "dark.toml", "-o", "out.png"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success() && dir.path().join("out.png").is_file(), "{stderr}");
    assert!(stderr.contains("dark.toml:4:1: warning in `render.integrator`: the scene has no light"), "{stderr}");
    // A light anywhere (here the background) silences it, and classic never warns.
    for scene in [format!("{dark}[world]\nbackground = 0.5\n"), dark.replace("\"path\"", "\"classic\"")] {
        std::fs::write(dir.path().join("lit.toml"), scene).unwrap();
        let run = prism().current_dir(dir.path()).args(["render", "lit.toml", "-o", "out.png"]).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(run.status.success() && !stderr.contains("no light"), "{stderr}");
    }
}

/// POV-Ray's negative lights subtract light under classic; under path, where the scene's
/// own setting or `--integrator` puts it, such a light is an error naming its key.
#[test]
fn a_negative_light_renders_under_classic_only() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[render]\nwidth = 8\nheight = 6\n[[object]]\nshape = \"sphere\"\n\n[[light]]\nposition = [0, 5, -5]\n\
                 \n[[light]]\nposition = [0, 5, -5]\nintensity = -0.5\n";
    std::fs::write(dir.path().join("minus.toml"), scene).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "minus.toml", "-o", "classic.png"]).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let run = prism()
        .current_dir(dir.path())
        .args(["render", "minus.toml", "--integrator", "path", "-o", "path.png"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success() && !dir.path().join("path.png").exists(), "{stderr}");
    assert!(stderr.contains("minus.toml:12:1: error in `light[1].intensity`"), "{stderr}");
}

#[test]
fn missing_scene_file_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "no-such-scene.toml"]).output().unwrap();
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("no-such-scene.toml") && stderr.contains("cannot read scene file"), "{stderr}");
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn errors_are_all_reported_at_once() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), "[[object]]\nshape = \"sphear\"\n[[object]]\nshape = \"bx\"\n").unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "s.toml"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("s.toml:2:") && stderr.contains("s.toml:4:"), "{stderr}");
}

#[test]
fn each_problem_is_reported_once() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[[light]]\nposition = [0.0, 3.0, 0.0]\nbrightness = 2.0\nintensity = \"high\"\n";
    std::fs::write(dir.path().join("s.toml"), scene).unwrap();
    let run = prism().current_dir(dir.path()).args(["render", "s.toml"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(stderr.matches("unknown key `brightness`").count(), 1, "{stderr}");
    assert!(stderr.contains("did you mean `tightness`?"), "{stderr}");
    assert!(stderr.contains("s.toml:4:") && stderr.contains("intensity"), "the rest is still checked: {stderr}");
    assert!(!run.status.success());
}

#[test]
fn default_command_renders_the_room() {
    let dir = tempfile::tempdir().unwrap();
    let run = prism().current_dir(dir.path()).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let img = image::open(dir.path().join("prism.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1000, 563));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("Mrays/s") && stderr.contains("primary rays"), "summary line: {stderr}");
    // The left wall is red, the right wall green.
    let left = img.get_pixel(20, 280).0;
    let right = img.get_pixel(980, 280).0;
    assert!(left[0] > left[1] + 40 && right[1] > right[0] + 40, "{left:?} {right:?}");
}

#[test]
fn shapes_lists_parameters_from_the_plugins() {
    let run = prism().arg("shapes").output().unwrap();
    assert!(run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    for needle in ["sphere", "radius", "plane", "normal", "cone", "base_radius", "disc", "cylinder", "box", "triangle"]
    {
        assert!(out.contains(needle), "`prism shapes` lacks {needle}:\n{out}");
    }
}

#[test]
fn help_is_available_everywhere() {
    for args in [
        vec!["--help"],
        vec!["render", "--help"],
        vec!["shapes", "--help"],
        vec!["save", "--help"],
        vec!["schema", "--help"],
    ] {
        let run = prism().args(&args).output().unwrap();
        assert!(run.status.success(), "{args:?}");
        assert!(String::from_utf8_lossy(&run.stdout).contains("Usage"), "{args:?}");
    }
}

#[test]
fn schema_is_json_with_every_shape() {
    let run = prism().arg("schema").output().unwrap();
    assert!(run.status.success());
    let schema: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let text = schema.to_string();
    for shape in ["sphere", "torus", "superellipsoid", "blob", "capsule"] {
        assert!(text.contains(&format!("\"{shape}\"")), "{shape} missing");
    }
}

/// A PNG of `width` x `height` grey texels.
fn grey_png(width: u32, height: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(png::ColorType::Grayscale);
    e.write_header().unwrap().write_image_data(&vec![128; (width * height) as usize]).unwrap();
    out
}

/// Every problem with an `image_map`'s or a `bump_map`'s file or keys names the scene file,
/// line and key,
/// exits non-zero and writes nothing.
#[test]
fn image_map_problems_name_the_file_and_key() {
    let object = |map: &str| format!("[[object]]\nshape = \"sphere\"\nmaterial = {{ pigment = {{ {map} }} }}\n");
    let bumped = |map: &str| format!("[[object]]\nshape = \"sphere\"\nmaterial = {{ normal = {{ {map} }} }}\n");
    let mut truncated = grey_png(4, 4);
    truncated.truncate(45);
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        ("missing", object("image_map = { file = \"nothere.png\" }"), vec!["nothere.png"]),
        ("not a PNG", object("image_map = { file = \"text.png\" }"), vec!["image_map reads PNG files"]),
        ("truncated", object("image_map = { file = \"truncated.png\" }"), vec!["cannot decode image"]),
        ("huge", object("image_map = { file = \"huge.png\" }"), vec!["40000 x 1", "longer than the limit"]),
        (
            "unknown map_type",
            object("image_map = { file = \"ok.png\", map_type = \"sphrical\" }"),
            vec!["map_type", "did you mean `spherical`"],
        ),
        (
            "pattern and image_map",
            object("pattern = \"checker\", colors = [[1, 1, 1], [0, 0, 0]], image_map = { file = \"ok.png\" }"),
            vec!["object[0].material.pigment.image_map", "not both"],
        ),
        (
            "color_map beside image_map",
            object("image_map = { file = \"ok.png\" }, color_map = [[0, [1, 1, 1]]]"),
            vec!["object[0].material.pigment.color_map", "belongs to a `pattern`"],
        ),
        (
            "missing in a pigment_map entry",
            object(
                "pattern = \"onion\", pigment_map = [[0, { color = [1, 1, 1] }], [1, { image_map = { file = \"nothere.png\" } }]]",
            ),
            vec!["nothere.png", "object[0].material.pigment.pigment_map[1][1].image_map.file"],
        ),
        (
            "infinite transmit_all",
            object("image_map = { file = \"ok.png\", transmit_all = inf }"),
            vec!["object[0].material.pigment.image_map.transmit_all", "finite"],
        ),
        (
            "use_index on an image_map pigment",
            object("image_map = { file = \"ok.png\", use_index = true }"),
            vec!["object[0].material.pigment.image_map.use_index", "`bump_map`"],
        ),
        (
            "missing bump_map",
            bumped("bump_map = { file = \"nothere.png\" }"),
            vec!["nothere.png", "object[0].material.normal.bump_map.file"],
        ),
        (
            "bump_map not a PNG",
            bumped("bump_map = { file = \"text.png\" }, bump_size = 2"),
            vec!["object[0].material.normal.bump_map.file", "PNG"],
        ),
        (
            "missing bump_map in a normal_map entry",
            bumped(
                "pattern = \"bozo\", normal_map = [[0, { pattern = \"bumps\" }], [1, { bump_map = { file = \"nothere.png\" } }]]",
            ),
            vec!["nothere.png", "object[0].material.normal.normal_map[1][1].bump_map.file"],
        ),
        (
            "filter_all on a bump_map",
            bumped("bump_map = { file = \"ok.png\", filter_all = 0.5 }"),
            vec!["object[0].material.normal.bump_map.filter_all", "`image_map` pigment"],
        ),
        (
            "unknown key in a bump_map",
            bumped("bump_map = { file = \"ok.png\", interpolat = \"bilinear\" }"),
            vec!["interpolat", "did you mean `interpolate`"],
        ),
        (
            "pattern and bump_map",
            bumped("pattern = \"bumps\", bump_map = { file = \"ok.png\" }"),
            vec!["object[0].material.normal.bump_map", "not both"],
        ),
        (
            "zero image_map repeat",
            object("image_map = { file = \"ok.png\", repeat = [0, 1] }"),
            vec!["object[0].material.pigment.image_map.repeat", "above 0"],
        ),
        (
            "infinite bump_map offset",
            bumped("bump_map = { file = \"ok.png\", offset = [inf, 0] }"),
            vec!["object[0].material.normal.bump_map.offset", "finite"],
        ),
        (
            "one-number repeat",
            object("image_map = { file = \"ok.png\", repeat = [2] }"),
            vec!["object[0].material.pigment.image_map.repeat", "length 2"],
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("text.png"), "not an image").unwrap();
    std::fs::write(dir.path().join("truncated.png"), &truncated).unwrap();
    std::fs::write(dir.path().join("huge.png"), grey_png(40_000, 1)).unwrap();
    std::fs::write(dir.path().join("ok.png"), grey_png(2, 2)).unwrap();
    let mut failures = Vec::new();
    for (name, scene, mut expect) in cases {
        std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
        let before = files_in(dir.path());
        let run = prism()
            .current_dir(dir.path())
            .args(["render", "scene.toml", "-o", "out.png", "--width", "8", "--height", "6"])
            .output()
            .unwrap();
        expect.push("scene.toml:3:");
        let mut problems = failed_run_problems(&run, &expect);
        if files_in(dir.path()) != before {
            problems.push("wrote a file".to_string());
        }
        if !problems.is_empty() {
            failures.push(format!("{name}: {}\n{}", problems.join("; "), String::from_utf8_lossy(&run.stderr)));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
