//! NTRT's builders: its defaults, a file's `builders` after those loaded before, and the
//! builder a pair takes (module docs of [`super`], "Members").

use super::*;

impl Loader {
    /// NTRT's default builders, overridden by any of the same tag.
    pub(super) fn default_builders(&mut self) {
        for (tag, class) in [("rod", "tgRodInfo"), ("string", "tgBasicActuatorInfo")] {
            self.builders.push(BuilderSpec {
                tag: tag.into(),
                words: vec![tag.into()],
                class: class.into(),
                parameters: Yaml::Null,
                file: "NTRT's defaults".into(),
            });
        }
    }

    /// The file's builders, after those loaded before.
    pub(super) fn add_builders(&mut self, builders: &Yaml, file: &str) -> Result<(), IoError> {
        let builders = builders
            .as_hash()
            .ok_or_else(|| bad(file, "builders", "give a map of tag: {class, parameters}"))?;
        for (tag, spec) in builders {
            let tag = scalar_name(tag);
            let class = spec["class"]
                .as_str()
                .ok_or_else(|| bad(file, &format!("builder {tag}"), "give its class"))?;
            self.builders.push(BuilderSpec {
                words: tag.split_whitespace().map(str::to_string).collect(),
                tag,
                class: class.to_string(),
                parameters: spec["parameters"].clone(),
                file: file.to_string(),
            });
        }
        Ok(())
    }

    /// The builder of a pair: among those whose words are all among its tags, the last of a
    /// rod class, else the last of a string class, else the last of any.
    pub(super) fn builder_of(&self, pair: &Pair) -> Option<&BuilderSpec> {
        let matching = || {
            (self.builders.iter().rev()).filter(|b| b.words.iter().all(|w| pair.tags.contains(w)))
        };
        matching()
            .find(|b| ROD_CLASSES.contains(&b.class.as_str()))
            .or_else(|| matching().find(|b| STRING_CLASSES.contains(&b.class.as_str())))
            .or_else(|| matching().next())
    }
}
