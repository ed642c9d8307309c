//! pbrt-v4's scene format read into statements: a directive (`Shape`, `LookAt`, …), its
//! positional arguments, and its typed parameters (`"float radius" [1]`), each with the file,
//! line and column it came from. `Include` and `Import` are read in place (a cycle refused);
//! files are found beside the first scene file, as pbrt-v4 finds them. The converter marks the
//! parameters it reads, so what it does not read is refused by name ([`Params::finish`]).
//!
//! Written here rather than taken from the `pbrt4` crate: its errors carry no line or column,
//! its transforms are f32, and it builds pbrt's scene objects where the import needs the
//! statements as written.

use crate::error::{cut, Result};
use crate::import::Place;
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// One token of a pbrt file.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    /// A quoted string, its escapes resolved.
    Quoted(String),
    /// A bare word: a directive, a number, `true` or `false`.
    Word(String),
    /// `[`.
    Open,
    /// `]`.
    Close,
}

/// The tokens of one file's text, with their places.
fn tokens(text: &str, file: &Rc<PathBuf>) -> Result<Vec<(Token, Place)>> {
    let mut out = Vec::new();
    let (mut line, mut col) = (1, 1);
    let mut chars = text.chars().peekable();
    let place = |line, col| Place {
        file: file.clone(),
        line,
        col,
    };
    while let Some(c) = chars.next() {
        let at = place(line, col);
        let advance = |c: char, line: &mut usize, col: &mut usize| match c {
            '\n' => {
                *line += 1;
                *col = 1;
            }
            _ => *col += 1,
        };
        advance(c, &mut line, &mut col);
        match c {
            c if c.is_whitespace() => {}
            '#' => {
                while let Some(&n) = chars.peek() {
                    if n == '\n' {
                        break;
                    }
                    chars.next();
                    advance(n, &mut line, &mut col);
                }
            }
            '[' => out.push((Token::Open, at)),
            ']' => out.push((Token::Close, at)),
            '"' => {
                let mut s = String::new();
                loop {
                    let Some(n) = chars.next() else {
                        return Err(at.error("a string is not closed (no ending \")"));
                    };
                    advance(n, &mut line, &mut col);
                    match n {
                        '"' => break,
                        '\n' => return Err(at.error("a string runs past the end of its line")),
                        '\\' => {
                            let Some(e) = chars.next() else {
                                return Err(at.error("a string is not closed (no ending \")"));
                            };
                            advance(e, &mut line, &mut col);
                            s.push(match e {
                                'n' => '\n',
                                't' => '\t',
                                other => other,
                            });
                        }
                        other => s.push(other),
                    }
                }
                out.push((Token::Quoted(s), at));
            }
            c => {
                let mut s = String::from(c);
                while let Some(&n) = chars.peek() {
                    if n.is_whitespace() || matches!(n, '"' | '[' | ']' | '#') {
                        break;
                    }
                    s.push(n);
                    chars.next();
                    advance(n, &mut line, &mut col);
                }
                out.push((Token::Word(s), at));
            }
        }
    }
    Ok(out)
}

/// A parameter's value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A number.
    Number(f64),
    /// A quoted string.
    Text(String),
    /// `true` or `false`.
    Bool(bool),
}

/// A typed parameter, `"type name" value` or `"type name" [values]`.
#[derive(Debug)]
pub struct Param {
    /// Its type as written (`float`, `rgb`, `point3`, …).
    pub ty: String,
    /// Its name.
    pub name: String,
    /// Its values.
    pub values: Vec<Value>,
    /// Where it was written.
    pub place: Place,
    read: Cell<bool>,
}

impl Param {
    /// The numbers of a parameter of type `types` (one of them), each checked finite.
    fn numbers(&self, types: &[&str]) -> Result<Vec<f64>> {
        if !types.contains(&self.ty.as_str()) {
            return Err(self.place.error(format!(
                "\"{} {}\": expected the type {}",
                cut(&self.ty),
                cut(&self.name),
                types.join(" or ")
            )));
        }
        self.values
            .iter()
            .map(|v| match v {
                Value::Number(x) if x.is_finite() => Ok(*x),
                other => Err(self.place.error(format!(
                    "\"{} {}\": {other:?} is not a finite number",
                    cut(&self.ty),
                    cut(&self.name)
                ))),
            })
            .collect()
    }

    /// What a message calls it: `"type name"`.
    pub fn what(&self) -> String {
        format!("\"{} {}\"", cut(&self.ty), cut(&self.name))
    }
}

/// The parameters of one statement.
#[derive(Debug, Default)]
pub struct Params(Vec<Param>);

impl Params {
    /// The parameter `name`, marked read.
    pub fn take(&self, name: &str) -> Option<&Param> {
        let p = self.0.iter().find(|p| p.name == name)?;
        p.read.set(true);
        Some(p)
    }

    /// How many values its parameters hold in all (none marked read).
    pub fn values(&self) -> usize {
        self.0.iter().map(|p| p.values.len()).sum()
    }

    /// Whether `name` is given (not marked read).
    pub fn has(&self, name: &str) -> bool {
        self.0.iter().any(|p| p.name == name)
    }

    /// Marks `name` read: a parameter that changes nothing grinlight renders.
    pub fn ignore(&self, name: &str) {
        self.take(name);
    }

    /// One number of a parameter of type `types`.
    fn one(&self, name: &str, types: &[&str]) -> Result<Option<f64>> {
        let Some(p) = self.take(name) else {
            return Ok(None);
        };
        match p.numbers(types)?[..] {
            [x] => Ok(Some(x)),
            ref v => Err(p.place.error(format!(
                "{}: expected one number, got {}",
                p.what(),
                v.len()
            ))),
        }
    }

    /// A `float` (`default` when absent).
    pub fn float(&self, name: &str, default: f64) -> Result<f64> {
        Ok(self.one(name, &["float"])?.unwrap_or(default))
    }

    /// An `integer` (`default` when absent).
    pub fn integer(&self, name: &str, default: i64) -> Result<i64> {
        match self.one(name, &["integer"])? {
            None => Ok(default),
            Some(x) if x.fract() == 0.0 && x.abs() < 2f64.powi(53) => Ok(x as i64),
            Some(x) => Err(self.take(name).expect("read above").place.error(format!(
                "\"integer {}\": {x} is not a whole number",
                cut(name)
            ))),
        }
    }

    /// The numbers of a parameter of one of `types` (None when absent).
    pub fn numbers(&self, name: &str, types: &[&str]) -> Result<Option<(Vec<f64>, &Param)>> {
        match self.take(name) {
            None => Ok(None),
            Some(p) => Ok(Some((p.numbers(types)?, p))),
        }
    }

    /// A `string` (None when absent).
    pub fn string(&self, name: &str) -> Result<Option<String>> {
        let Some(p) = self.take(name) else {
            return Ok(None);
        };
        match (p.ty.as_str(), &p.values[..]) {
            ("string" | "texture", [Value::Text(s)]) => Ok(Some(s.clone())),
            _ => Err(p
                .place
                .error(format!("{}: expected one quoted string", p.what()))),
        }
    }

    /// A `bool` (`default` when absent).
    pub fn boolean(&self, name: &str, default: bool) -> Result<bool> {
        let Some(p) = self.take(name) else {
            return Ok(default);
        };
        match (p.ty.as_str(), &p.values[..]) {
            ("bool", [Value::Bool(b)]) => Ok(*b),
            _ => Err(p
                .place
                .error(format!("{}: expected one bool, true or false", p.what()))),
        }
    }

    /// Refuses the first parameter not read, naming it and `owner`.
    pub fn finish(&self, owner: &str) -> Result<()> {
        match self.0.iter().find(|p| !p.read.get()) {
            None => Ok(()),
            Some(p) => Err(p.place.error(format!(
                "{owner}: the parameter {} is not supported by grinlight's import",
                p.what()
            ))),
        }
    }
}

/// A positional argument.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// A quoted string.
    Text(String),
    /// A number.
    Number(f64),
}

/// One statement: a directive, its positional arguments and its parameters.
#[derive(Debug)]
pub struct Statement {
    /// The directive as written (`Shape`, `LookAt`, …).
    pub directive: String,
    /// Where the directive was written.
    pub place: Place,
    /// Its positional arguments (strings and numbers, a bracketed list flattened).
    pub args: Vec<Arg>,
    /// Its parameters.
    pub params: Params,
}

impl Statement {
    /// The `i`th positional argument as a string.
    pub fn text(&self, i: usize) -> &str {
        match self.args.get(i) {
            Some(Arg::Text(s)) => s,
            _ => "",
        }
    }

    /// The positional arguments as numbers.
    pub fn numbers(&self) -> Vec<f64> {
        self.args
            .iter()
            .filter_map(|a| match a {
                Arg::Number(x) => Some(*x),
                Arg::Text(_) => None,
            })
            .collect()
    }

    /// What a message calls it: the directive and its first string, `Shape "sphere"`.
    pub fn what(&self) -> String {
        match self.args.first() {
            Some(Arg::Text(s)) => format!("{} \"{}\"", self.directive, cut(s)),
            _ => self.directive.clone(),
        }
    }
}

/// What follows a directive before its parameters.
#[derive(Clone, Copy)]
enum Shape {
    /// Nothing (and no parameters).
    Bare,
    /// `n` numbers, bracketed or not (and no parameters).
    Numbers(usize),
    /// `n` quoted strings, then parameters.
    Strings(usize),
    /// One or two quoted strings (`MediumInterface`), no parameters.
    OneOrTwoStrings,
    /// Parameters only (`Option`).
    ParamsOnly,
}

/// pbrt-v4's directives and what each takes.
fn shape_of(directive: &str) -> Option<Shape> {
    Some(match directive {
        "WorldBegin" | "AttributeBegin" | "AttributeEnd" | "TransformBegin" | "TransformEnd"
        | "Identity" | "ReverseOrientation" | "ObjectEnd" | "WorldEnd" => Shape::Bare,
        "Translate" | "Scale" => Shape::Numbers(3),
        "Rotate" => Shape::Numbers(4),
        "LookAt" => Shape::Numbers(9),
        "Transform" | "ConcatTransform" => Shape::Numbers(16),
        "TransformTimes" => Shape::Numbers(2),
        "Camera" | "Film" | "Sampler" | "PixelFilter" | "Integrator" | "Accelerator" | "Shape"
        | "Material" | "LightSource" | "AreaLightSource" | "MakeNamedMaterial"
        | "MakeNamedMedium" | "Attribute" | "NamedMaterial" | "CoordinateSystem"
        | "CoordSysTransform" | "ColorSpace" | "ObjectBegin" | "ObjectInstance" | "Include"
        | "Import" | "ActiveTransform" => Shape::Strings(1),
        "Texture" => Shape::Strings(3),
        "MediumInterface" => Shape::OneOrTwoStrings,
        "Option" => Shape::ParamsOnly,
        _ => return None,
    })
}

/// A pbrt scene's statements, every included file read in place.
pub struct Scene {
    /// The statements in order.
    pub statements: Vec<Statement>,
    /// The files read.
    pub files: Vec<PathBuf>,
    /// The directory files are found in: the first scene file's.
    pub dir: PathBuf,
}

impl Scene {
    /// A file the scene names, found beside the first scene file (or as given, if absolute).
    pub fn find(&self, name: &str, place: &Place) -> Result<PathBuf> {
        let path = self.dir.join(name);
        if let Some(why) = crate::input::not_regular(&path) {
            return Err(place.error(format!("\"{}\" {why}", cut(name))));
        }
        match path.is_file() {
            true => Ok(path),
            false => Err(place.error(format!(
                "the file \"{}\" is not found (looked for at {})",
                cut(name),
                path.display()
            ))),
        }
    }
}

/// Reads the pbrt scene `path` and every file it includes.
pub fn read(path: &Path) -> Result<Scene> {
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let mut scene = Scene {
        statements: Vec::new(),
        files: Vec::new(),
        dir,
    };
    let mut stack = Vec::new();
    read_file(path, None, &mut scene, &mut stack)?;
    Ok(scene)
}

fn read_file(
    path: &Path,
    from: Option<&Place>,
    scene: &mut Scene,
    stack: &mut Vec<PathBuf>,
) -> Result<()> {
    let canonical = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let cannot = |message: String| match from {
        Some(place) => place.error(message),
        None => crate::error::Error::Usage(message),
    };
    if stack.contains(&canonical) {
        return Err(cannot(format!(
            "{} includes itself (through {})",
            path.display(),
            stack
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(" → ")
        )));
    }
    if let Some(why) = crate::input::not_regular(path) {
        return Err(cannot(format!("{}: {why}", path.display())));
    }
    // Read whole; its tokens take a few times its bytes (a compressed file's several more).
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    crate::resources::check_memory(size.saturating_mul(24), "reading this pbrt file")
        .map_err(|e| cannot(format!("{}: {e}", path.display())))?;
    let raw =
        std::fs::read(path).map_err(|e| cannot(format!("cannot read {}: {e}", path.display())))?;
    // pbrt reads a gzip-compressed file (`.pbrt.gz`) as its text.
    let bytes = match raw.starts_with(&[0x1f, 0x8b]) {
        true => {
            let mut plain = Vec::new();
            std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&raw[..]), &mut plain)
                .map_err(|e| {
                    cannot(format!(
                        "{}: the gzip-compressed data is damaged ({e})",
                        path.display()
                    ))
                })?;
            plain
        }
        false => raw,
    };
    let text = String::from_utf8(bytes)
        .map_err(|_| cannot(format!("{}: the file is not UTF-8 text", path.display())))?;
    let file = Rc::new(path.to_path_buf());
    scene.files.push(path.to_path_buf());
    stack.push(canonical);
    let toks = tokens(&text, &file)?;
    let mut i = 0;
    while i < toks.len() {
        let (tok, place) = &toks[i];
        let Token::Word(directive) = tok else {
            return Err(place.error(format!(
                "expected a directive (Shape, LookAt, …), found {}",
                describe(tok)
            )));
        };
        let shape = shape_of(directive).ok_or_else(|| {
            place.error(format!("'{}' is not a pbrt-v4 directive", cut(directive)))
        })?;
        i += 1;
        let mut args = Vec::new();
        let mut params = Params::default();
        let number = |t: &Token, p: &Place| -> Result<f64> {
            match t {
                Token::Word(w) => w
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| p.error(format!("expected a number, found '{}'", cut(w)))),
                other => Err(p.error(format!("expected a number, found {}", describe(other)))),
            }
        };
        let quoted = |i: usize| -> Result<String> {
            match toks.get(i) {
                Some((Token::Quoted(s), _)) => Ok(s.clone()),
                Some((other, p)) => Err(p.error(format!(
                    "{directive}: expected a quoted string, found {}",
                    describe(other)
                ))),
                None => Err(place.error(format!(
                    "{directive}: expected a quoted string, found the end of the file"
                ))),
            }
        };
        let mut with_params = false;
        match shape {
            Shape::Bare => {}
            Shape::Numbers(n) => {
                let bracketed = matches!(toks.get(i), Some((Token::Open, _)));
                if bracketed {
                    i += 1;
                }
                for _ in 0..n {
                    let Some((t, p)) = toks.get(i) else {
                        return Err(place.error(format!(
                            "{directive}: expected {n} numbers, found the end of the file"
                        )));
                    };
                    args.push(Arg::Number(number(t, p).map_err(|_| {
                        p.error(format!(
                            "{directive}: expected {n} numbers, found {}",
                            describe(t)
                        ))
                    })?));
                    i += 1;
                }
                if bracketed {
                    match toks.get(i) {
                        Some((Token::Close, _)) => i += 1,
                        _ => {
                            return Err(
                                place.error(format!("{directive}: expected {n} numbers and ]"))
                            )
                        }
                    }
                }
            }
            Shape::Strings(n) => {
                for _ in 0..n {
                    args.push(Arg::Text(quoted(i)?));
                    i += 1;
                }
                with_params = true;
            }
            Shape::OneOrTwoStrings => {
                args.push(Arg::Text(quoted(i)?));
                i += 1;
                if let Some((Token::Quoted(s), _)) = toks.get(i) {
                    args.push(Arg::Text(s.clone()));
                    i += 1;
                }
            }
            Shape::ParamsOnly => with_params = true,
        }
        if with_params {
            while let Some((Token::Quoted(decl), p)) = toks.get(i) {
                let words: Vec<&str> = decl.split_whitespace().collect();
                let [ty, name] = words[..] else {
                    return Err(p.error(format!(
                        "{directive}: \"{}\" is not a parameter declaration (\"type name\")",
                        cut(decl)
                    )));
                };
                i += 1;
                let mut values = Vec::new();
                let value = |t: &Token, p: &Place| -> Result<Value> {
                    match t {
                        Token::Quoted(s) => Ok(Value::Text(s.clone())),
                        Token::Word(w) if w == "true" => Ok(Value::Bool(true)),
                        Token::Word(w) if w == "false" => Ok(Value::Bool(false)),
                        Token::Word(_) => number(t, p).map(Value::Number),
                        other => Err(p.error(format!(
                            "\"{}\": expected a value, found {}",
                            cut(decl),
                            describe(other)
                        ))),
                    }
                };
                match toks.get(i) {
                    Some((Token::Open, _)) => {
                        i += 1;
                        loop {
                            match toks.get(i) {
                                Some((Token::Close, _)) => {
                                    i += 1;
                                    break;
                                }
                                Some((t, vp)) => values.push(value(t, vp)?),
                                None => {
                                    return Err(p.error(format!(
                                        "\"{}\": the list is not closed (no ])",
                                        cut(decl)
                                    )))
                                }
                            }
                            i += 1;
                        }
                    }
                    Some((t, vp)) => {
                        values.push(value(t, vp)?);
                        i += 1;
                    }
                    None => {
                        return Err(p.error(format!(
                            "\"{}\": no value follows, the file ends",
                            cut(decl)
                        )))
                    }
                }
                // pbrt writes a bool quoted or bare.
                if ty == "bool" {
                    for v in &mut values {
                        if let Value::Text(s) = v {
                            match s.as_str() {
                                "true" => *v = Value::Bool(true),
                                "false" => *v = Value::Bool(false),
                                _ => {}
                            }
                        }
                    }
                }
                if params.has(name) {
                    return Err(p.error(format!(
                        "{directive}: the parameter '{}' is given twice",
                        cut(name)
                    )));
                }
                params.0.push(Param {
                    ty: ty.to_string(),
                    name: name.to_string(),
                    values,
                    place: p.clone(),
                    read: Cell::new(false),
                });
            }
        }
        let statement = Statement {
            directive: directive.clone(),
            place: place.clone(),
            args,
            params,
        };
        match directive.as_str() {
            "Include" | "Import" => {
                let name = statement.text(0).to_string();
                let target = scene.find(&name, &statement.place)?;
                read_file(&target, Some(&statement.place), scene, stack)?;
            }
            _ => scene.statements.push(statement),
        }
    }
    stack.pop();
    Ok(())
}

fn describe(t: &Token) -> String {
    match t {
        Token::Quoted(s) => format!("\"{}\"", cut(s)),
        Token::Word(w) => format!("'{}'", cut(w)),
        Token::Open => "[".into(),
        Token::Close => "]".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_keep_their_places_and_comments_are_skipped() {
        let file = Rc::new(PathBuf::from("s.pbrt"));
        let t = tokens("# c\nShape \"sphere\" \"float radius\" [ 2 ]\n", &file).unwrap();
        let kinds: Vec<&Token> = t.iter().map(|(k, _)| k).collect();
        assert_eq!(
            kinds,
            [
                &Token::Word("Shape".into()),
                &Token::Quoted("sphere".into()),
                &Token::Quoted("float radius".into()),
                &Token::Open,
                &Token::Word("2".into()),
                &Token::Close
            ]
        );
        assert_eq!((t[0].1.line, t[0].1.col), (2, 1));
        assert_eq!((t[2].1.line, t[2].1.col), (2, 16));
    }
}
