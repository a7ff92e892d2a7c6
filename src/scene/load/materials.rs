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
        self.material_textures(index, key, &mut material)
            .then(|| MaterialComponent::authored(None, std::sync::Arc::new(material)))
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
