//! Substructures: loading the files a model names, and placing the children (every
//! rotation first, then scale, offset and translation per child; module docs of [`super`]).

use super::geometry::*;
use super::*;

impl Loader {
    /// Loads the substructures of a file and places them (module docs: rotations first,
    /// then scale, offset and translation per child).
    pub(super) fn substructures(
        &mut self,
        subs: &Yaml,
        file: &str,
        dir: &Path,
        prefix: &str,
        depth: usize,
    ) -> Result<Vec<Tree>, IoError> {
        let subs = subs
            .as_hash()
            .ok_or_else(|| bad(file, "substructures", "give a map of name: {path, …}"))?;
        let mut entries = Vec::with_capacity(subs.len());
        for (key, attributes) in subs {
            let key = scalar_name(key);
            let item = format!("substructure {key}");
            let attributes = attributes.as_hash().ok_or_else(|| {
                bad(
                    file,
                    &item,
                    "give a map of path, rotation, scale, translation, offset",
                )
            })?;
            for a in attributes.keys() {
                let a = scalar_name(a);
                if !matches!(
                    a.as_str(),
                    "path" | "rotation" | "translation" | "scale" | "offset"
                ) {
                    return Err(bad(file, &item, format!("`{a}` is not a substructure attribute (path, rotation, scale, translation, offset)")));
                }
            }
            let names: Vec<String> = key.split('/').map(str::to_string).collect();
            if names
                .iter()
                .any(|n| n.is_empty() || n.contains('.') || n.contains(char::is_whitespace))
            {
                return Err(bad(file, &item, "a substructure name is not empty and has no `.` or space (`a/b/c` names three)"));
            }
            entries.push((names, attributes));
        }
        let mut children: Vec<Tree> = Vec::new();
        for (names, attributes) in &entries {
            let Some(path) = attributes.get(&Yaml::String("path".into())) else {
                continue;
            };
            for name in names {
                let item = format!("substructure {name}");
                if children.iter().any(|c| c.name == *name) {
                    return Err(bad(file, &item, "given a path twice"));
                }
                let path = path
                    .as_str()
                    .ok_or_else(|| bad(file, &item, "its path is a file name"))?;
                let mut tree = self.load_child(
                    file,
                    dir,
                    name,
                    path,
                    &format!("{prefix}{name}."),
                    depth + 1,
                )?;
                tree.name = name.clone();
                children.push(tree);
            }
        }
        self.turn(&children, &entries, file)?;
        self.shift(&children, &entries, file)?;
        Ok(children)
    }

    /// The children's rotations (all before any other transform, as in NTRT).
    pub(super) fn turn(
        &mut self,
        children: &[Tree],
        entries: &[Entry],
        file: &str,
    ) -> Result<(), IoError> {
        for (names, attributes) in entries {
            let Some(rotation) = attributes.get(&Yaml::String("rotation".into())) else {
                continue;
            };
            for name in names {
                let c = child(children, name, file)?;
                let item = format!("substructure {name}");
                let axis = vec3(&rotation["axis"])
                    .filter(|a| a.iter().any(|x| *x != 0.0))
                    .ok_or_else(|| bad(file, &item, "a rotation's axis is a non-zero [x, y, z]"))?;
                let angle = number(&rotation["angle"])
                    .filter(|a| a.is_finite())
                    .ok_or_else(|| bad(file, &item, "a rotation's angle is a number (degrees)"))?;
                let reference = match &rotation["reference"] {
                    Yaml::BadValue | Yaml::Null => self.centre(&children[c].nodes),
                    r => vec3(r)
                        .ok_or_else(|| bad(file, &item, "a rotation's reference is [x, y, z]"))?,
                };
                let range = children[c].nodes.clone();
                for p in &mut self.points[range] {
                    *p = rotate(*p, reference, axis, angle.to_radians());
                }
            }
        }
        Ok(())
    }

    /// Per child: its scale (about its centre), its offset (k times it for the k-th name of
    /// a slash series) and its translation.
    pub(super) fn shift(
        &mut self,
        children: &[Tree],
        entries: &[Entry],
        file: &str,
    ) -> Result<(), IoError> {
        for (names, attributes) in entries {
            let get = |key: &str| attributes.get(&Yaml::String(key.into()));
            for (k, name) in names.iter().enumerate() {
                let c = child(children, name, file)?;
                let item = format!("substructure {name}");
                let range = children[c].nodes.clone();
                if let Some(scale) = get("scale") {
                    let s = number(scale)
                        .filter(|s| s.is_finite() && *s != 0.0)
                        .ok_or_else(|| bad(file, &item, "its scale is a non-zero number"))?;
                    let centre = self.centre(&range);
                    for p in &mut self.points[range.clone()] {
                        *p = std::array::from_fn(|d| centre[d] + s * (p[d] - centre[d]));
                    }
                }
                let mut shift = [0.0; 3];
                if let Some(offset) = get("offset") {
                    let o =
                        vec3(offset).ok_or_else(|| bad(file, &item, "its offset is [x, y, z]"))?;
                    shift = std::array::from_fn(|d| o[d] * k as f64);
                }
                if let Some(translation) = get("translation") {
                    let t = vec3(translation)
                        .ok_or_else(|| bad(file, &item, "its translation is [x, y, z]"))?;
                    shift = std::array::from_fn(|d| shift[d] + t[d]);
                }
                for p in &mut self.points[range] {
                    *p = std::array::from_fn(|d| p[d] + shift[d]);
                }
            }
        }
        Ok(())
    }

    /// Reads, parses and loads one substructure file (`path`, relative to `dir`).
    pub(super) fn load_child(
        &mut self,
        file: &str,
        dir: &Path,
        name: &str,
        path: &str,
        prefix: &str,
        depth: usize,
    ) -> Result<Tree, IoError> {
        let item = format!("substructure {name}");
        let child_path = dir.join(path);
        let label = child_path.display().to_string();
        if depth > MAX_DEPTH {
            return Err(bad(
                file,
                &item,
                format!("substructures nest deeper than {MAX_DEPTH} files (at {label})"),
            ));
        }
        self.structures += 1;
        if self.structures > MAX_STRUCTURES {
            return Err(bad(
                file,
                &item,
                format!("the model has more than {MAX_STRUCTURES} substructures"),
            ));
        }
        let unreadable = |e: IoError| bad(file, &item, format!("{e}"));
        let canonical = std::fs::canonicalize(&child_path).map_err(|source| {
            unreadable(IoError::Read {
                path: child_path.clone(),
                source,
            })
        })?;
        if let Some(k) = self.stack.iter().position(|p| *p == canonical) {
            let chain: Vec<String> = (self.stack[k..].iter())
                .chain([&canonical])
                .map(|p| p.display().to_string())
                .collect();
            return Err(bad(
                file,
                &item,
                format!("{label} includes itself: {}", chain.join(" → ")),
            ));
        }
        let root = match self.cache.get(&canonical) {
            Some(root) => root.clone(),
            None => {
                let text = crate::read::read_text(
                    &child_path,
                    crate::read::MAX_SCENE_BYTES,
                    "an NTRT model",
                )
                .map_err(unreadable)?;
                let root = parse(&text, &label)?;
                self.cache.insert(canonical.clone(), root.clone());
                root
            }
        };
        let child_dir = child_path.parent().unwrap_or(Path::new("")).to_path_buf();
        self.stack.push(canonical);
        let tree = self.load(&root, &label, &child_dir, prefix, depth);
        self.stack.pop();
        tree
    }

    /// The mean of the nodes in `range` (the origin for none).
    pub(super) fn centre(&self, range: &Range<usize>) -> [f64; 3] {
        let n = range.len().max(1) as f64;
        let mut c = [0.0; 3];
        for p in &self.points[range.clone()] {
            for d in 0..3 {
                c[d] += p[d];
            }
        }
        c.map(|x| x / n)
    }
}
