//! The one-off that made `assets/env/`: an OpenEXR environment map (2:1) averaged down by an
//! integer factor in each axis (each output texel the mean of a block of input texels) and
//! written as `.exr` (f32, ZIP) or `.hdr` by the output path's extension. Negative texels
//! (the ringing of lossy DWA compression, which the Blender maps use) are set to 0 first and
//! counted: [`EnvironmentMap`] refuses negative radiance.
//!
//! ```sh
//! cargo run --release --example env_downscale -- ../shared/assets/hdri/blender-studiolights/sunset.exr 4 assets/env/sunset_256x128.exr
//! ```

use std::path::PathBuf;

use prism::texture::environment::EnvironmentMap;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, factor, output] = args.as_slice() else {
        return Err("usage: env_downscale INPUT FACTOR OUTPUT".into());
    };
    let (input, output) = (PathBuf::from(input), PathBuf::from(output));
    let factor: usize = factor.parse()?;
    let source = exr::prelude::read_first_rgba_layer_from_file(
        &input,
        |size, _| (size.width(), vec![[0.0f32; 3]; size.area()]),
        |(width, texels): &mut (usize, Vec<[f32; 3]>),
         at: exr::prelude::Vec2<usize>,
         (r, g, b, _): (f32, f32, f32, f32)| {
            texels[at.y() * *width + at.x()] = [r, g, b];
        },
    )?;
    let (source_width, mut source_texels) = source.layer_data.channel_data.pixels;
    let negative = source_texels.iter().flatten().filter(|c| **c < 0.0).count();
    let lowest = source_texels.iter().flatten().fold(0.0f32, |a, &c| a.min(c));
    source_texels.iter_mut().flatten().for_each(|c| *c = c.max(0.0));
    let map = EnvironmentMap::from_texels(source_width, source_texels.len() / source_width, source_texels)?;
    println!("{}: {negative} negative components set to 0 (lowest {lowest:e})", input.display());
    let (w, h) = (map.width() / factor, map.height() / factor);
    if w * factor != map.width() || h * factor != map.height() {
        return Err(format!("{} x {} is not divisible by {factor}", map.width(), map.height()).into());
    }
    let mut texels = vec![[0.0f32; 3]; w * h];
    for (i, texel) in texels.iter_mut().enumerate() {
        let (x, y) = (i % w, i / w);
        let mut sum = [0.0f64; 3];
        for dy in 0..factor {
            for dx in 0..factor {
                let t = map.texel(x * factor + dx, y * factor + dy);
                for c in 0..3 {
                    sum[c] += f64::from(t[c]);
                }
            }
        }
        *texel = sum.map(|s| (s / (factor * factor) as f64) as f32);
    }
    match output.extension().and_then(|e| e.to_str()) {
        Some("exr") => {
            use exr::prelude::*;
            let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
                let t = texels[p.y() * w + p.x()];
                (t[0], t[1], t[2])
            });
            let layer = Layer::new((w, h), LayerAttributes::default(), Encoding::SMALL_LOSSLESS, channels);
            Image::from_layer(layer).write().to_file(&output)?;
        }
        Some("hdr") => {
            let data: Vec<f32> = texels.iter().flatten().copied().collect();
            let image = image::Rgb32FImage::from_raw(w as u32, h as u32, data).ok_or("size mismatch")?;
            image::DynamicImage::ImageRgb32F(image).save(&output)?;
        }
        _ => return Err("the output must be .exr or .hdr".into()),
    }
    let written = EnvironmentMap::load(&output)?;
    println!("{}: {} x {}, power {:.4} (source {:.4})", output.display(), w, h, written.power(), map.power());
    Ok(())
}
