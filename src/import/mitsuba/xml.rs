//! Mitsuba 3's scene XML read into a tree of objects: `<default>` values and `$name`
//! substitution (the command line's `-D name=value` first), `<include>` (a cycle refused),
//! `<path>`, `id` and `<ref>`, typed properties and `<transform>`s. Every object, property and
//! error keeps the file, line and column it came from; the converter marks what it reads, so
//! what it does not read can be refused by name ([`Object::finish`]).

use crate::error::{cut, Error, Result};
use crate::import::geometry::look_at;
pub use crate::import::Place;
use glam::{DMat4, DVec3};
use std::cell::Cell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// A property's value, as its element's name types it.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `<float>`.
    Float(f64),
    /// `<integer>`.
    Integer(i64),
    /// `<boolean>`.
    Boolean(bool),
    /// `<string>`.
    String(String),
    /// `<point>` or `<vector>`.
    Vector(DVec3),
    /// `<rgb>`.
    Rgb(DVec3),
    /// `<spectrum value="v">`: the same value at every wavelength.
    UniformSpectrum(f64),
    /// `<spectrum value="…">` given by wavelength–value pairs (the attribute's text).
    SampledSpectrum(String),
    /// `<spectrum filename="…">`: a spectrum in a file.
    SpectrumFile(String),
    /// `<transform>`: the product of its operations, the first applied first.
    Transform(DMat4),
}

impl Value {
    /// The element name that gives such a value.
    fn kind(&self) -> &'static str {
        match self {
            Value::Float(_) => "float",
            Value::Integer(_) => "integer",
            Value::Boolean(_) => "boolean",
            Value::String(_) => "string",
            Value::Vector(_) => "point or vector",
            Value::Rgb(_) => "rgb",
            Value::UniformSpectrum(_) | Value::SampledSpectrum(_) | Value::SpectrumFile(_) => {
                "spectrum"
            }
            Value::Transform(_) => "transform",
        }
    }
}

/// A named property of an object.
#[derive(Debug)]
pub struct Property {
    /// Its `name`.
    pub name: String,
    /// Its value.
    pub value: Value,
    /// Where it was written.
    pub place: Place,
    used: Cell<bool>,
}

/// A nested object (or a `<ref>` to one, which may come before the object it names, as
/// Mitsuba allows), with the name it is given (`<texture name="reflectance">`).
#[derive(Debug)]
pub struct Child {
    /// Its `name` attribute, if any.
    pub name: Option<String>,
    /// The object (a `<ref>`'s, once the whole scene is read).
    object: std::cell::OnceCell<Rc<Object>>,
    /// The id a `<ref>` names.
    reference: Option<String>,
    /// Where it (or the `<ref>`) was written.
    pub place: Place,
    used: Cell<bool>,
}

impl Child {
    fn owned(name: Option<String>, object: Rc<Object>, place: Place) -> Child {
        Child {
            name,
            object: std::cell::OnceCell::from(object),
            reference: None,
            place,
            used: Cell::new(false),
        }
    }

    /// The object.
    pub fn object(&self) -> &Rc<Object> {
        self.object
            .get()
            .expect("references are resolved when the scene is read")
    }
}

/// A plugin object: `<shape type="sphere" id="...">` with its properties and nested objects.
#[derive(Debug)]
pub struct Object {
    /// The element: `scene`, `shape`, `bsdf`, `emitter`, `sensor`, `film`, ….
    pub tag: String,
    /// Its `type` (the plugin; empty for the scene).
    pub kind: String,
    /// Its `id`, if any.
    pub id: Option<String>,
    /// Where it was written.
    pub place: Place,
    properties: Vec<Property>,
    children: Vec<Child>,
}

/// The elements that make an object.
const OBJECT_TAGS: [&str; 12] = [
    "shape",
    "bsdf",
    "emitter",
    "sensor",
    "film",
    "sampler",
    "integrator",
    "medium",
    "phase",
    "texture",
    "rfilter",
    "volume",
];

impl Object {
    /// `<tag type="kind">` as messages name it.
    pub fn what(&self) -> String {
        match self.id.as_deref() {
            Some(id) => format!("<{} type=\"{}\" id=\"{id}\">", self.tag, self.kind),
            None => format!("<{} type=\"{}\">", self.tag, self.kind),
        }
    }

    /// An error at this object naming it.
    pub fn error(&self, message: impl std::fmt::Display) -> Error {
        self.place.error(format!("{}: {message}", self.what()))
    }

    /// The property `name`, marked as read.
    pub fn property(&self, name: &str) -> Option<&Property> {
        let p = self.properties.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    /// Whether the object has the property `name` (not marking it read).
    pub fn has(&self, name: &str) -> bool {
        self.properties.iter().any(|p| p.name == name)
            || self
                .children
                .iter()
                .any(|c| c.name.as_deref() == Some(name))
    }

    /// Reads past the property `name`: it changes nothing grinlight computes.
    pub fn ignore(&self, name: &str) {
        self.property(name);
    }

    fn wrong_type(&self, p: &Property, expected: &str) -> Error {
        p.place.error(format!(
            "{}: parameter '{}' should be a {expected}, got a {}",
            self.what(),
            p.name,
            p.value.kind()
        ))
    }

    /// A float (an integer is one too).
    pub fn float(&self, name: &str) -> Result<Option<f64>> {
        match self.property(name) {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Float(x) => Ok(Some(x)),
                Value::Integer(i) => Ok(Some(i as f64)),
                _ => Err(self.wrong_type(p, "float")),
            },
        }
    }

    /// A float, or `default`.
    pub fn float_or(&self, name: &str, default: f64) -> Result<f64> {
        Ok(self.float(name)?.unwrap_or(default))
    }

    /// An integer, or `default`.
    pub fn integer_or(&self, name: &str, default: i64) -> Result<i64> {
        match self.property(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Integer(i) => Ok(i),
                _ => Err(self.wrong_type(p, "integer")),
            },
        }
    }

    /// A boolean, or `default`.
    pub fn boolean_or(&self, name: &str, default: bool) -> Result<bool> {
        match self.property(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Boolean(b) => Ok(b),
                _ => Err(self.wrong_type(p, "boolean")),
            },
        }
    }

    /// A string.
    pub fn string(&self, name: &str) -> Result<Option<&str>> {
        match self.property(name) {
            None => Ok(None),
            Some(p) => match &p.value {
                Value::String(s) => Ok(Some(s)),
                _ => Err(self.wrong_type(p, "string")),
            },
        }
    }

    /// A point or vector.
    pub fn vector(&self, name: &str) -> Result<Option<DVec3>> {
        match self.property(name) {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Vector(v) => Ok(Some(v)),
                _ => Err(self.wrong_type(p, "point or vector")),
            },
        }
    }

    /// A transform (the identity where none is given).
    pub fn transform(&self, name: &str) -> Result<DMat4> {
        match self.property(name) {
            None => Ok(DMat4::IDENTITY),
            Some(p) => match p.value {
                Value::Transform(m) => Ok(m),
                _ => Err(self.wrong_type(p, "transform")),
            },
        }
    }

    /// The nested objects of element `tag`, marked as read.
    pub fn children(&self, tag: &str) -> Vec<&Child> {
        let found: Vec<&Child> = self
            .children
            .iter()
            .filter(|c| c.object().tag == tag)
            .collect();
        found.iter().for_each(|c| c.used.set(true));
        found
    }

    /// The nested object called `name` (`<texture name="reflectance">`), marked as read.
    pub fn named_child(&self, name: &str) -> Option<&Child> {
        let c = self
            .children
            .iter()
            .find(|c| c.name.as_deref() == Some(name))?;
        c.used.set(true);
        Some(c)
    }

    /// The one nested object of element `tag` (None: none; two are an error).
    pub fn child(&self, tag: &str) -> Result<Option<&Child>> {
        match self.children(tag).as_slice() {
            [] => Ok(None),
            [one] => Ok(Some(one)),
            [_, second, ..] => Err(second
                .place
                .error(format!("{}: more than one <{tag}>", self.what()))),
        }
    }

    /// Every property and nested object was read: the first one that was not is refused by
    /// name (grinlight cannot convert it).
    pub fn finish(&self) -> Result<()> {
        if let Some(p) = self.properties.iter().find(|p| !p.used.get()) {
            return Err(p.place.error(format!(
                "{}: parameter '{}' is not supported by grinlight's import",
                self.what(),
                p.name
            )));
        }
        if let Some(c) = self.children.iter().find(|c| !c.used.get()) {
            return Err(c.place.error(format!(
                "{}: a nested {} is not supported here by grinlight's import",
                self.what(),
                c.object().what()
            )));
        }
        Ok(())
    }

    /// Every nested object, read or not (for the scene's top level).
    pub fn all_children(&self) -> &[Child] {
        &self.children
    }

    /// Marks a nested object as read.
    pub fn mark(child: &Child) {
        child.used.set(true);
    }
}

/// A Mitsuba scene read from its files: the top-level `<scene>` and every file it read.
pub struct Document {
    /// The `<scene>`.
    pub scene: Rc<Object>,
    /// The XML files read (the scene and its includes).
    pub files: Vec<PathBuf>,
    /// Where the files a scene names are looked for, in order: the directories `<path>`
    /// added (the last first), then the scene file's own (Mitsuba's file resolver).
    pub search: Vec<PathBuf>,
}

impl Document {
    /// A file the scene names (see [`find_in`]).
    pub fn find(&self, relative: &str, from: &Place) -> Result<PathBuf> {
        find_in(relative, from, &self.search)
    }
}

/// A file a scene names: looked for as Mitsuba does, relative to `search` (the `<path>`
/// directories, then the scene file's directory — also for a name in an included file), and
/// last beside the file that names it.
fn find_in(relative: &str, from: &Place, search: &[PathBuf]) -> Result<PathBuf> {
    let own = from.file.parent().unwrap_or(Path::new(".")).to_path_buf();
    search
        .iter()
        .cloned()
        .chain(std::iter::once(own))
        .map(|dir| dir.join(relative))
        .find(|p| p.exists())
        .ok_or_else(|| {
            let dirs: Vec<String> = search.iter().map(|d| d.display().to_string()).collect();
            from.error(format!(
                "'{}' not found in {} (the scene's directory and its <path>s)",
                cut(relative),
                dirs.join(", ")
            ))
        })
}

/// Reads the scene `path`, `defines` (`-D name=value`) before its `<default>`s.
pub fn read(path: &Path, defines: &[(String, String)]) -> Result<Document> {
    let mut reader = Reader {
        values: defines.iter().cloned().collect(),
        ids: HashMap::new(),
        search: vec![path.parent().unwrap_or(Path::new(".")).to_path_buf()],
        including: Vec::new(),
        files: Vec::new(),
    };
    let mut scene = Object {
        tag: "scene".into(),
        kind: String::new(),
        id: None,
        place: Place {
            file: Rc::new(path.to_path_buf()),
            line: 1,
            col: 1,
        },
        properties: Vec::new(),
        children: Vec::new(),
    };
    reader.file(path, &mut scene)?;
    resolve(&scene, &reader.ids)?;
    Ok(Document {
        scene: Rc::new(scene),
        files: reader.files,
        search: reader.search,
    })
}

/// Points every `<ref>` under `object` at the object of its id (anywhere in the scene: a
/// reference may come before the object, as Mitsuba reads them).
fn resolve(object: &Object, ids: &HashMap<String, Rc<Object>>) -> Result<()> {
    for child in &object.children {
        match &child.reference {
            Some(id) => {
                let target = ids.get(id).ok_or_else(|| {
                    child
                        .place
                        .error(format!("<ref id=\"{}\">: no object has this id", cut(id)))
                })?;
                child.object.get_or_init(|| target.clone());
            }
            None => resolve(child.object(), ids)?,
        }
    }
    Ok(())
}

struct Reader {
    /// `$name` values: the command line's, then each `<default>` not given there.
    values: HashMap<String, String>,
    ids: HashMap<String, Rc<Object>>,
    search: Vec<PathBuf>,
    /// The files being read, outermost first (an include of one of them is a cycle).
    including: Vec<PathBuf>,
    files: Vec<PathBuf>,
}

/// A node's place in its file.
fn place_of(file: &Rc<PathBuf>, doc: &roxmltree::Document, node: roxmltree::Node) -> Place {
    let pos = doc.text_pos_at(node.range().start);
    Place {
        file: file.clone(),
        line: pos.row as usize,
        col: pos.col as usize,
    }
}

impl Reader {
    /// Reads a file's `<scene>` into `into` (the scene, or the scene including it).
    fn file(&mut self, path: &Path, into: &mut Object) -> Result<()> {
        let text =
            crate::input::read_text(path, crate::input::MAX_SCENE_BYTES, "a Mitsuba scene file")?;
        let file = Rc::new(path.to_path_buf());
        let doc = roxmltree::Document::parse(&text).map_err(|e| {
            let pos = e.pos();
            Place {
                file: file.clone(),
                line: pos.row as usize,
                col: pos.col as usize,
            }
            .error(format!("malformed XML: {e}"))
        })?;
        let root = doc.root_element();
        let place = place_of(&file, &doc, root);
        if root.tag_name().name() != "scene" {
            return Err(place.error(format!(
                "expected a Mitsuba <scene>, found <{}>",
                cut(root.tag_name().name())
            )));
        }
        let version = root
            .attribute("version")
            .ok_or_else(|| place.error("<scene> has no version (Mitsuba 2 and 3 write one)"))?;
        let major = version.split('.').next().unwrap_or("");
        if !(major == "2" || major == "3") {
            return Err(place.error(format!(
                "<scene version=\"{}\">: only Mitsuba 2 and 3 scenes (version 2.x or 3.x) are \
                 read; upgrade older ones with Mitsuba's own tools",
                cut(version)
            )));
        }
        self.files.push(path.to_path_buf());
        self.including.push(canonical(path));
        self.children(&file, &doc, root, into)?;
        self.including.pop();
        Ok(())
    }

    /// An attribute with `$name`s replaced.
    fn attribute(
        &self,
        node: roxmltree::Node,
        name: &str,
        place: &Place,
    ) -> Result<Option<String>> {
        node.attribute(name)
            .map(|raw| self.substitute(raw, place))
            .transpose()
    }

    fn required(&self, node: roxmltree::Node, name: &str, place: &Place) -> Result<String> {
        self.attribute(node, name, place)?.ok_or_else(|| {
            place.error(format!(
                "<{}> needs a '{name}' attribute",
                node.tag_name().name()
            ))
        })
    }

    fn substitute(&self, raw: &str, place: &Place) -> Result<String> {
        let mut out = String::new();
        let mut rest = raw;
        while let Some(at) = rest.find('$') {
            out.push_str(&rest[..at]);
            let after = &rest[at + 1..];
            let len = after
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(after.len());
            let name = &after[..len];
            if name.is_empty() {
                return Err(place.error(format!("'$' without a name in \"{}\"", cut(raw))));
            }
            let value = self.values.get(name).ok_or_else(|| {
                place.error(format!(
                    "'${name}' has no value: the scene gives it no <default>; give it on the \
                     command line with -D {name}=VALUE"
                ))
            })?;
            out.push_str(value);
            rest = &after[len..];
        }
        out.push_str(rest);
        Ok(out)
    }

    fn children(
        &mut self,
        file: &Rc<PathBuf>,
        doc: &roxmltree::Document,
        node: roxmltree::Node,
        into: &mut Object,
    ) -> Result<()> {
        for child in node.children().filter(|n| n.is_element()) {
            let place = place_of(file, doc, child);
            let tag = child.tag_name().name();
            match tag {
                "default" => {
                    let name = self.required(child, "name", &place)?;
                    let value = self.required(child, "value", &place)?;
                    self.values.entry(name).or_insert(value);
                }
                "include" => {
                    let name = self.required(child, "filename", &place)?;
                    let path = find_in(&name, &place, &self.search)?;
                    if self.including.contains(&canonical(&path)) {
                        return Err(place.error(format!(
                            "<include filename=\"{}\"> includes a file that is being read \
                             (a cycle)",
                            cut(&name)
                        )));
                    }
                    if into.tag != "scene" {
                        return Err(place.error("<include> is read only at a scene's top level"));
                    }
                    self.file(&path, into)?;
                }
                "path" => {
                    let value = self.required(child, "value", &place)?;
                    let dir = file.parent().unwrap_or(Path::new(".")).join(value);
                    self.search.insert(0, dir);
                }
                "ref" => {
                    let id = self.required(child, "id", &place)?;
                    into.children.push(Child {
                        name: self.attribute(child, "name", &place)?,
                        object: std::cell::OnceCell::new(),
                        reference: Some(id),
                        place,
                        used: Cell::new(false),
                    });
                }
                "spectrum" if child.attribute("type").is_some() => {
                    return Err(place.error(format!(
                        "<spectrum type=\"{}\">: only a spectrum given by value is read",
                        cut(child.attribute("type").unwrap_or_default())
                    )));
                }
                t if OBJECT_TAGS.contains(&t) => {
                    let object = self.object(file, doc, child, place.clone())?;
                    let name = self.attribute(child, "name", &place)?;
                    into.children.push(Child::owned(name, object, place));
                }
                _ => {
                    let name = self
                        .required(child, "name", &place)
                        .map_err(|_| place.error(format!("unknown element <{}>", cut(tag))))?;
                    let value = self.value(file, doc, child, &place)?;
                    if into.properties.iter().any(|p| p.name == name) {
                        return Err(place.error(format!(
                            "{}: parameter '{}' is given twice",
                            into.what(),
                            cut(&name)
                        )));
                    }
                    into.properties.push(Property {
                        name,
                        value,
                        place,
                        used: Cell::new(false),
                    });
                }
            }
        }
        Ok(())
    }

    fn object(
        &mut self,
        file: &Rc<PathBuf>,
        doc: &roxmltree::Document,
        node: roxmltree::Node,
        place: Place,
    ) -> Result<Rc<Object>> {
        let tag = node.tag_name().name().to_string();
        let kind = self.required(node, "type", &place)?;
        let id = self.attribute(node, "id", &place)?;
        let mut object = Object {
            tag,
            kind,
            id: id.clone(),
            place: place.clone(),
            properties: Vec::new(),
            children: Vec::new(),
        };
        self.children(file, doc, node, &mut object)?;
        let object = Rc::new(object);
        if let Some(id) = id {
            if self.ids.insert(id.clone(), object.clone()).is_some() {
                return Err(place.error(format!("id \"{}\" is given to two objects", cut(&id))));
            }
        }
        Ok(object)
    }

    /// A property element's value.
    fn value(
        &self,
        file: &Rc<PathBuf>,
        doc: &roxmltree::Document,
        node: roxmltree::Node,
        place: &Place,
    ) -> Result<Value> {
        let tag = node.tag_name().name();
        let value = |s: &Self| s.required(node, "value", place);
        let bad = |text: &str, what: &str| {
            place.error(format!("<{tag}>: \"{}\" is not {what}", cut(text)))
        };
        Ok(match tag {
            "float" => {
                let v = value(self)?;
                Value::Float(number(&v).ok_or_else(|| bad(&v, "a number"))?)
            }
            "integer" => {
                let v = value(self)?;
                Value::Integer(v.trim().parse().map_err(|_| bad(&v, "an integer"))?)
            }
            "boolean" => {
                let v = value(self)?;
                Value::Boolean(match v.trim().to_ascii_lowercase().as_str() {
                    "true" => true,
                    "false" => false,
                    _ => return Err(bad(&v, "true or false")),
                })
            }
            "string" => Value::String(value(self)?),
            "point" | "vector" => Value::Vector(self.vector(node, place, 0.0)?),
            "rgb" => {
                let v = value(self)?;
                match numbers(&v).as_deref() {
                    Some([x]) => Value::Rgb(DVec3::splat(*x)),
                    Some([r, g, b]) => Value::Rgb(DVec3::new(*r, *g, *b)),
                    _ => return Err(bad(&v, "one or three numbers")),
                }
            }
            "spectrum" => match node.attribute("filename") {
                Some(f) => Value::SpectrumFile(self.substitute(f, place)?),
                None => {
                    let v = value(self)?;
                    match number(&v) {
                        Some(x) => Value::UniformSpectrum(x),
                        None => Value::SampledSpectrum(v),
                    }
                }
            },
            "transform" => Value::Transform(self.transform(file, doc, node)?),
            _ => return Err(place.error(format!("unknown element <{}>", cut(tag)))),
        })
    }

    /// `x`, `y`, `z` attributes (each `default` when missing) or `value="x y z"`.
    fn vector(&self, node: roxmltree::Node, place: &Place, default: f64) -> Result<DVec3> {
        if let Some(v) = self.attribute(node, "value", place)? {
            return match numbers(&v).as_deref() {
                Some([x, y, z]) => Ok(DVec3::new(*x, *y, *z)),
                Some([s]) => Ok(DVec3::splat(*s)),
                _ => Err(place.error(format!(
                    "<{}>: value \"{}\" is not three numbers",
                    node.tag_name().name(),
                    cut(&v)
                ))),
            };
        }
        let mut out = DVec3::splat(default);
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            if let Some(s) = self.attribute(node, axis, place)? {
                out[i] = number(&s).ok_or_else(|| {
                    place.error(format!(
                        "<{}>: {axis}=\"{}\" is not a number",
                        node.tag_name().name(),
                        cut(&s)
                    ))
                })?;
            }
        }
        Ok(out)
    }

    /// A `<transform>`: its operations in order, each applied after the ones before.
    fn transform(
        &self,
        file: &Rc<PathBuf>,
        doc: &roxmltree::Document,
        node: roxmltree::Node,
    ) -> Result<DMat4> {
        let mut m = DMat4::IDENTITY;
        for op in node.children().filter(|n| n.is_element()) {
            let place = place_of(file, doc, op);
            let step = match op.tag_name().name() {
                "translate" => DMat4::from_translation(self.vector(op, &place, 0.0)?),
                "scale" => DMat4::from_scale(self.vector(op, &place, 1.0)?),
                "rotate" => {
                    let axis = self.vector(op, &place, 0.0)?;
                    let angle = self.required(op, "angle", &place)?;
                    let angle = number(&angle)
                        .ok_or_else(|| place.error("<rotate>: angle is not a number"))?;
                    if axis == DVec3::ZERO || !axis.is_finite() {
                        return Err(place.error("<rotate>: the axis is zero"));
                    }
                    DMat4::from_mat3(rotation_as_given(axis, angle.to_radians()))
                }
                "matrix" => {
                    let v = self.required(op, "value", &place)?;
                    match numbers(&v).as_deref() {
                        Some(n) if n.len() == 16 => DMat4::from_cols_slice(n).transpose(),
                        Some(n) if n.len() == 9 => {
                            DMat4::from_mat3(glam::DMat3::from_cols_slice(n).transpose())
                        }
                        _ => {
                            return Err(place
                                .error("<matrix>: value should be 16 numbers (or 9), row by row"))
                        }
                    }
                }
                "lookat" => {
                    let at = |name: &str| -> Result<DVec3> {
                        let v = self.required(op, name, &place)?;
                        match numbers(&v).as_deref() {
                            Some([x, y, z]) => Ok(DVec3::new(*x, *y, *z)),
                            _ => Err(place.error(format!(
                                "<lookat>: {name}=\"{}\" is not three numbers",
                                cut(&v)
                            ))),
                        }
                    };
                    look_at(at("origin")?, at("target")?, at("up")?).ok_or_else(|| {
                        place.error("<lookat>: origin = target, or up is along the view")
                    })?
                }
                other => {
                    return Err(
                        place.error(format!("<transform>: unknown operation <{}>", cut(other)))
                    )
                }
            };
            m = step * m;
        }
        if !m.is_finite() {
            return Err(place_of(file, doc, node).error("<transform>: not finite"));
        }
        Ok(m)
    }
}

/// A path to compare with the files being read (itself where it cannot be resolved).
fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// One finite number.
fn number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Finite numbers separated by commas or spaces.
fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(number)
        .collect()
}

/// Mitsuba's `<rotate>` by `angle` (radians) about `axis` as given (Dr.Jit's `rotate`, which
/// does not normalise it): Rodrigues' R = cos θ I + sin θ [a]× + (1 − cos θ) a aᵀ — a rotation
/// for a unit axis; one of any other length also scales and shears, and Mitsuba renders the
/// shape so (its `hello.xml` turns a teapot about (0, 1, 1)).
fn rotation_as_given(a: DVec3, angle: f64) -> glam::DMat3 {
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    glam::DMat3::from_cols(
        DVec3::new(
            c + t * a.x * a.x,
            t * a.x * a.y + s * a.z,
            t * a.x * a.z - s * a.y,
        ),
        DVec3::new(
            t * a.x * a.y - s * a.z,
            c + t * a.y * a.y,
            t * a.y * a.z + s * a.x,
        ),
        DVec3::new(
            t * a.x * a.z + s * a.y,
            t * a.y * a.z - s * a.x,
            c + t * a.z * a.z,
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_is_mitsubas_frame() {
        let m = look_at(
            DVec3::new(0.0, 1.0, 5.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::Y,
        )
        .unwrap();
        // Looking down −z with +y up, Mitsuba's camera +x is the viewer's left: world −x.
        assert!((m.transform_vector3(DVec3::X) - DVec3::NEG_X).length() < 1e-15);
        assert!((m.transform_vector3(DVec3::Z) - DVec3::NEG_Z).length() < 1e-15);
        assert!((m.transform_point3(DVec3::ZERO) - DVec3::new(0.0, 1.0, 5.0)).length() < 1e-15);
    }

    #[test]
    fn numbers_take_commas_and_spaces() {
        assert_eq!(numbers("1, 2 3"), Some(vec![1.0, 2.0, 3.0]));
        assert_eq!(numbers("1, x"), None);
        assert_eq!(numbers("inf"), None);
    }
}
