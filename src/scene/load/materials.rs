//! `[materials]` and inline materials: deserialising them and loading their textures.

use super::*;

impl Loader<'_> {
    pub(super) fn materials(&mut self, index: usize, value: &toml::Value) {
        let toml::Value::Table(table) = value else {
            self.diagnostics.push(Diagnostic::new(
                self.files[index].locate_value("materials"),
                "`materials` must be a table of named materials",
            ));
            return;
        };
        for (name, def) in table {
            let key = format!("materials.{name}");
            if let Some(material) = self.material(index, &key, def.clone()) {
                let named = MaterialComponent { name: Some(name.clone()), ..material };
                self.materials.insert(name.clone(), (named, index));
            }
        }
    }

    /// A scene material (inline, or the definition of a named one) as an unnamed component.
    pub(super) fn material(&mut self, index: usize, key: &str, value: toml::Value) -> Option<MaterialComponent> {
        let mut material: MaterialSpec = self.deserialize(index, key, value)?;
        if let Err((field, message)) = material.check() {
            let k = format!("{key}.{field}");
            self.diagnostics.push(Diagnostic::new(self.files[index].locate(&k), message));
            return None;
        }
        let textures = self.material_textures(index, key, &mut material);
        let image_map = self.material_image_map(index, key, &mut material);
        (textures && image_map).then(|| MaterialComponent::authored(None, std::sync::Arc::new(material)))
    }

    /// Resolves and decodes the PNGs of a material's image maps (`pigment.image_map`, in
    /// layers and `pigment_map` entries too; relative to scene file `index`), as every image a
    /// scene names is read; reports a problem at its `file`.
    fn material_image_map(&mut self, index: usize, key: &str, material: &mut MaterialSpec) -> bool {
        let mut ok = true;
        for (path, map, raw) in material.image_maps_mut() {
            ok &= self.image_map(index, &format!("{key}.{path}.file"), map, raw);
        }
        ok
    }

    /// Resolves and decodes one image map's PNG (`raw`: a bump map's, without gamma); reports
    /// a problem at `file_key`.
    fn image_map(
        &mut self,
        index: usize,
        file_key: &str,
        map: &mut crate::material::image_map::ImageMap,
        raw: bool,
    ) -> bool {
        let at = self.files[index].locate(file_key);
        let path = match self.access.join(&self.directory(index), &map.file) {
            Ok(path) => path,
            Err(e) => {
                self.diagnostics.push(Diagnostic::new(at, e.to_string()));
                return false;
            }
        };
        let canonical = match self.access.resolve(&path) {
            Ok(canonical) => canonical,
            Err(e) => {
                self.diagnostics.push(Diagnostic::new(at, e.to_string()));
                return false;
            }
        };
        if let Some(image) = self.image_maps.get(&(canonical.clone(), raw)) {
            map.image = Some(image.clone());
            map.path = Some(canonical);
            return true;
        }
        let store = &mut self.meshes.textures;
        let loaded = crate::material::image_map::load(&path, &self.access, store.budget(), raw, self.working_gamma);
        let loaded = match loaded {
            Err(crate::material::image_map::ImageMapError::Texture(crate::texture::TextureError::OverBudget(e))) => {
                Err(crate::texture::TextureError::OverBudget(store.restate(e)).into())
            }
            other => other,
        };
        let loaded = loaded.and_then(|image| {
            let estimate = crate::material::image_map::memory_estimate(image.width as u32, image.height as u32);
            store.reserve(|| format!("image `{}`", crate::files::shown_path(&path)), estimate).map_err(|e| {
                crate::material::image_map::ImageMapError::Texture(crate::texture::TextureError::OverBudget(e))
            })?;
            Ok(image)
        });
        match loaded {
            Ok(image) => {
                let image = std::sync::Arc::new(image);
                self.image_maps.insert((canonical.clone(), raw), image.clone());
                map.path = Some(canonical);
                map.image = Some(image);
                true
            }
            Err(e) => {
                self.diagnostics.push(Diagnostic::new(at, e.to_string()));
                false
            }
        }
    }

    /// Resolves the texture paths of a scene material (relative to scene file `index`) to
    /// absolute paths and decodes the images; reports unreadable images at `key`.
    pub(super) fn material_textures(&mut self, index: usize, key: &str, material: &mut MaterialSpec) -> bool {
        let dir = self.directory(index);
        let mut ok = true;
        for (texture, space) in material.textures_mut() {
            let path = match self.access.join(&dir, &texture.file) {
                Ok(path) => path,
                Err(e) => {
                    self.diagnostics.push(Diagnostic::new(self.files[index].locate(key), e.to_string()));
                    ok = false;
                    continue;
                }
            };
            match self.meshes.textures.load_file(&path, space) {
                Ok(t) => {
                    texture.file = std::fs::canonicalize(&path).unwrap_or(path).display().to_string();
                    texture.texture = Some(t);
                }
                Err(e) => {
                    self.diagnostics.push(Diagnostic::new(self.files[index].locate(key), e.to_string()));
                    ok = false;
                }
            }
        }
        ok
    }
}
