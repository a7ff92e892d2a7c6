//! `[[light]]` tables: each kind's keys, checked before deserialising.

use super::*;

impl Loader<'_> {
    pub(super) fn light(&mut self, index: usize, key: &str, table: toml::Table) -> Option<Light> {
        let kind = match table.get("kind") {
            None => LightKind::Point,
            Some(v) => self.deserialize::<LightKind>(index, &format!("{key}.kind"), v.clone())?,
        };
        let allowed = kind.allowed_keys();
        let mut ok = true;
        let mut reported = Vec::new();
        for k in table.keys() {
            if k != "kind" && !allowed.contains(&k.as_str()) {
                let known_elsewhere = LightKind::Area.allowed_keys().contains(&k.as_str())
                    || LightKind::Spot.allowed_keys().contains(&k.as_str());
                let message = if known_elsewhere {
                    format!("key `{k}` does not apply to a {kind:?} light", kind = kind).to_lowercase()
                } else {
                    format!("unknown key `{k}`")
                };
                // Suggest among every light's keys (a misspelt `tightness` on a point light is
                // still most likely `tightness`), else list this kind's.
                let every_key = [LightKind::Area, LightKind::Spot].into_iter().flat_map(|kind| kind.allowed_keys());
                let help = match crate::diagnostics::nearest_name(k, every_key.copied().chain(["kind"])) {
                    Some(name) => format!("did you mean `{name}`?"),
                    None => format!("valid keys here: kind, {}", allowed.join(", ")),
                };
                let d = Diagnostic::new(self.files[index].locate(&format!("{key}.{k}")), message).with_help(help);
                self.diagnostics.push(d);
                reported.push(k.clone());
                ok = false;
            }
        }
        // The rest is still checked, without the keys reported above (serde would name the
        // first of them a second time).
        let mut table = table;
        for k in &reported {
            table.remove(k);
        }
        let light: Light = self.deserialize(index, key, toml::Value::Table(table))?;
        ok.then_some(light)
    }
}
