//! The film: what a render produces. A linear RGB beauty image plus optional named layers
//! (AOVs), covering a region of the full frame.

/// A half-open rectangle of pixels `[x0, x1) x [y0, y1)` in full-frame coordinates (row 0 at
/// the top), as pbrt's `--pixelbounds`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Region {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Region {
    /// The whole `width` x `height` frame.
    pub fn full(width: u32, height: u32) -> Self {
        Self { x0: 0, y0: 0, x1: width, y1: height }
    }

    /// Columns covered.
    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    /// Rows covered.
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Pixels covered.
    pub fn pixel_count(&self) -> usize {
        self.width() as usize * self.height() as usize
    }

    /// True when the region covers no pixel.
    pub fn is_empty(&self) -> bool {
        self.pixel_count() == 0
    }

    /// True when full-frame pixel (x, y) lies inside.
    pub fn contains(&self, x: u32, y: u32) -> bool {
        (self.x0..self.x1).contains(&x) && (self.y0..self.y1).contains(&y)
    }

    /// True when the region lies inside a `width` x `height` frame.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        self.x0 <= self.x1 && self.y0 <= self.y1 && self.x1 <= width && self.y1 <= height
    }
}

/// Per-pixel data besides the beauty image, for compositing and denoising.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Aov {
    /// Reflectance of the first visible surface (linear RGB, Intel Open Image Denoise's
    /// convention: the first non-specular hit's colour).
    Albedo,
    /// World-space unit shading normal of the first visible surface, facing the camera.
    Normal,
    /// Distance from the camera to the first visible surface along the camera ray (scene
    /// units; the largest finite f32 where the ray escapes).
    Depth,
    /// World-space position of the first visible surface.
    Position,
    /// Texture coordinates of the first visible surface.
    Uv,
    /// Index of the first visible primitive (load order), -1 where the ray escapes.
    ObjectId,
    /// Index of the first visible surface's material, -1 where the ray escapes.
    MaterialId,
    /// Estimated variance of the pixel's mean radiance per RGB channel: the variance of its
    /// samples over their count (0 with one sample).
    Variance,
    /// Samples the pixel took (fewer than `samples` where adaptive sampling stopped early).
    Samples,
    /// The beauty as rendered, before denoising: `--denoise` keeps it as this layer and
    /// writes the denoised image as the beauty. Not in [`Aov::ALL`]: nobody asks for it by
    /// name.
    Raw,
}

impl Aov {
    /// Every AOV, in the order layers are written.
    pub const ALL: [Aov; 9] = [
        Aov::Albedo,
        Aov::Normal,
        Aov::Depth,
        Aov::Position,
        Aov::Uv,
        Aov::ObjectId,
        Aov::MaterialId,
        Aov::Variance,
        Aov::Samples,
    ];

    /// The layer's name (EXR channels are `name.channel`).
    pub fn name(self) -> &'static str {
        match self {
            Aov::Albedo => "albedo",
            Aov::Normal => "normal",
            Aov::Depth => "depth",
            Aov::Position => "position",
            Aov::Uv => "uv",
            Aov::ObjectId => "object_id",
            Aov::MaterialId => "material_id",
            Aov::Variance => "variance",
            Aov::Samples => "samples",
            Aov::Raw => "raw",
        }
    }

    /// The layer's channel names, as compositors expect them.
    pub fn channels(self) -> &'static [&'static str] {
        match self {
            Aov::Albedo | Aov::Variance | Aov::Raw => &["R", "G", "B"],
            Aov::Normal | Aov::Position => &["X", "Y", "Z"],
            Aov::Depth => &["Z"],
            Aov::Uv => &["U", "V"],
            Aov::ObjectId | Aov::MaterialId => &["id"],
            Aov::Samples => &["count"],
        }
    }

    /// The AOV named `name`, if any.
    pub fn from_name(name: &str) -> Option<Aov> {
        Aov::ALL.into_iter().find(|a| a.name() == name)
    }

    /// True for layers made from the surface a pixel's first sample sees (not from all its
    /// samples).
    pub fn needs_first_hit(self) -> bool {
        !matches!(self, Aov::Variance | Aov::Samples | Aov::Raw)
    }

    /// The AOVs `names` name, in order and without repeats; an unknown name is an error
    /// that lists the known ones and suggests the nearest.
    pub fn parse_list<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<Vec<Aov>, String> {
        let mut aovs = Vec::new();
        for name in names {
            let name = name.trim();
            let aov = Aov::from_name(name).ok_or_else(|| {
                let known: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
                let near = crate::diagnostics::nearest_name(name, known.iter().copied())
                    .map_or(String::new(), |n| format!(" (did you mean `{n}`?)"));
                let shown: String = name.chars().take(40).map(|c| if c.is_control() { '?' } else { c }).collect();
                format!("unknown AOV `{shown}`{near}; known: {}", known.join(", "))
            })?;
            if !aovs.contains(&aov) {
                aovs.push(aov);
            }
        }
        Ok(aovs)
    }
}

/// One named layer of the film: `channels` floats per pixel, interleaved, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// What the layer holds.
    pub aov: Aov,
    /// `aov.channels().len()` values per pixel.
    pub data: Vec<f32>,
}

impl Layer {
    /// Values per pixel.
    pub fn channel_count(&self) -> usize {
        self.aov.channels().len()
    }
}

/// A linear, unclipped RGB image of a region of the frame, row-major from the region's
/// top-left pixel, with optional AOV layers of the same size.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width of the region in pixels.
    pub width: u32,
    /// Height of the region in pixels.
    pub height: u32,
    /// The full frame's size (equal to the region's when the whole image was rendered).
    pub frame: (u32, u32),
    /// The region's top-left pixel in the full frame.
    pub origin: (u32, u32),
    /// Beauty pixels (radiance), `width * height` of them.
    pub pixels: Vec<[f32; 3]>,
    /// AOV layers, in the order asked for.
    pub layers: Vec<Layer>,
}

impl Film {
    /// A black film of a whole `width` x `height` frame, without layers.
    pub fn new(width: u32, height: u32) -> Self {
        Self::for_region(Region::full(width, height), (width, height), &[])
    }

    /// A black film of `region` of a `frame`-sized image, with zeroed `aovs` layers.
    pub fn for_region(region: Region, frame: (u32, u32), aovs: &[Aov]) -> Self {
        let n = region.pixel_count();
        Self {
            width: region.width(),
            height: region.height(),
            frame,
            origin: (region.x0, region.y0),
            pixels: vec![[0.0; 3]; n],
            layers: aovs.iter().map(|&aov| Layer { aov, data: vec![0.0; n * aov.channels().len()] }).collect(),
        }
    }

    /// The region of the frame the film covers.
    pub fn region(&self) -> Region {
        let (x0, y0) = self.origin;
        Region { x0, y0, x1: x0 + self.width, y1: y0 + self.height }
    }

    /// True when the film covers the whole frame.
    pub fn is_full_frame(&self) -> bool {
        self.origin == (0, 0) && (self.width, self.height) == self.frame
    }

    /// The beauty pixel at column `x`, row `y` of the film (not of the frame).
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// The layer holding `aov`, if the film has one.
    pub fn layer(&self, aov: Aov) -> Option<&Layer> {
        self.layers.iter().find(|l| l.aov == aov)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn region_geometry() {
        let r = Region { x0: 2, y0: 1, x1: 5, y1: 3 };
        assert_eq!((r.width(), r.height(), r.pixel_count()), (3, 2, 6));
        assert!(r.contains(2, 1) && r.contains(4, 2) && !r.contains(5, 2) && !r.contains(2, 3));
        assert!(r.fits(5, 3) && !r.fits(4, 3));
        assert!(Region { x0: 3, y0: 0, x1: 2, y1: 1 }.is_empty());
    }

    #[test]
    fn film_of_a_region_knows_its_place() {
        let film = Film::for_region(Region { x0: 16, y0: 8, x1: 48, y1: 24 }, (64, 32), &[Aov::Normal, Aov::Depth]);
        assert_eq!((film.width, film.height, film.pixels.len()), (32, 16, 512));
        assert_eq!(film.region(), Region { x0: 16, y0: 8, x1: 48, y1: 24 });
        assert!(!film.is_full_frame());
        assert_eq!(film.layer(Aov::Normal).unwrap().data.len(), 512 * 3);
        assert_eq!(film.layer(Aov::Depth).unwrap().data.len(), 512);
        assert!(film.layer(Aov::Albedo).is_none());
        assert!(Film::new(4, 3).is_full_frame());
    }

    #[test]
    fn aov_names_round_trip() {
        for aov in Aov::ALL {
            assert_eq!(Aov::from_name(aov.name()), Some(aov));
        }
        assert_eq!(Aov::from_name("albedos"), None);
        assert_eq!(Aov::from_name("raw"), None, "the raw beauty is kept by --denoise, not asked for");
    }

    #[test]
    fn aov_lists_parse_with_suggestions() {
        assert_eq!(Aov::parse_list(["depth", " normal", "depth"]), Ok(vec![Aov::Depth, Aov::Normal]));
        let error = Aov::parse_list(["albedo", "normals"]).unwrap_err();
        assert!(error.contains("`normals`") && error.contains("did you mean `normal`?"), "{error}");
        assert!(Aov::parse_list([""]).is_err());
    }
}
