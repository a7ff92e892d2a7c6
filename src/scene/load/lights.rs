//! `[[light]]` tables: each kind's keys ([`LIGHT_KEYS`]), checked before deserialising.

use super::*;
use crate::world::components::LIGHT_KEYS;

impl Loader<'_> {
    pub(super) fn light(&mut self, index: usize, key: &str, table: toml::Table) -> Option<Light> {
        let kind = match table.get("kind") {
            None => LightKind::Point,
            Some(v) => self.deserialize::<LightKind>(index, &format!("{key}.kind"), v.clone())?,
        };
        let mut ok = true;
        let mut reported = Vec::new();
        for k in table.keys() {
            if k != "kind" && !kind.accepts(k) {
                let valid = || format!("valid keys here: kind, {}", kind.keys().collect::<Vec<_>>().join(", "));
                let (message, help) = if let Some((_, kinds)) = LIGHT_KEYS.iter().find(|(name, _)| name == k) {
                    // A real key on the wrong kind: say which kinds take it.
                    let takers: Vec<String> = kinds.iter().map(|other| format!("\"{}\"", other.name())).collect();
                    (
                        format!("key `{k}` does not apply to a {} light", kind.name()),
                        format!("`{k}` belongs to kind = {}; {}", takers.join(" or "), valid()),
                    )
                } else {
                    // Suggest among every light's keys (a misspelt `tightness` on a point light
                    // is still most likely `tightness`), else list this kind's.
                    let every_key = LIGHT_KEYS.iter().map(|(name, _)| *name);
                    let help = match crate::diagnostics::nearest_name(k, every_key.chain(["kind"])) {
                        Some(name) => format!("did you mean `{name}`?"),
                        None => valid(),
                    };
                    (format!("unknown key `{k}`"), help)
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
        let cone = light.kind == LightKind::Spot || (light.kind == LightKind::Area && light.spot);
        if cone && light.shadowless {
            // POV-Ray 3.7's parser keeps one light type, which `spotlight` and `shadowless`
            // each overwrite (Parse_Light_Source), so it has no cone-limited light without
            // shadows.
            let location = self.files[index].locate(&format!("{key}.shadowless"));
            let message = "a spot light cannot be shadowless: POV-Ray 3.7 has no such light (`spotlight \
                           shadowless` renders a shadowless point light with no cone, `shadowless spotlight` \
                           an ordinary spot that casts shadows)";
            let help = "for a shadowless light without a cone write kind = \"point\"; for a spot drop `shadowless`";
            self.diagnostics.push(Diagnostic::new(location, message).with_help(help));
            ok = false;
        }
        if cone && light.radius > light.falloff {
            // POV-Ray's cubic_spline(falloff, radius, cos) is 0 below cos(falloff) and 1 from
            // cos(radius) on; with the bounds crossed the cone has a hard edge at `radius`.
            let location = self.files[index].locate(&format!("{key}.radius"));
            let message = format!(
                "radius {} exceeds falloff {}: the spot has a hard edge at {} degrees and no soft falloff, as in POV-Ray",
                light.radius, light.falloff, light.radius
            );
            self.warnings
                .push(Diagnostic::warning(location, message).with_help("make falloff at least radius for a soft edge"));
        }
        ok.then_some(light)
    }
}
