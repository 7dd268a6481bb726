//! What the checker says about shapes: sections, profiles and their
//! outlines, regions with holes, and a loft's ends and spine.

use crate::diag::message::value::Got;
use crate::diag::{Code, Diagnostic};
use crate::span::Span;
use crate::units::{Angle, Length};

/// A rounded rectangle's corner radius is negative (`most` is `None`) or
/// larger than half its shorter side (`most` is that half).
pub fn corner_radius(r: Length, most: Option<Length>, at: Span) -> Diagnostic {
    let d = Diagnostic::error(
        Code::CornerRadius,
        "the corner radius must lie between 0 and half the shorter side",
    )
    .label(at, format!("this is {r}"));
    match most {
        None => d.help("a corner radius is 0 (sharp) or more"),
        Some(m) => d.help(format!("use a radius of at most {m}")),
    }
}

/// Two arguments giving the same size (`a` and `b`) are both written.
pub fn either_not_both(a: &str, a_at: Option<Span>, b: &str, b_at: Option<Span>) -> Diagnostic {
    Diagnostic::error(
        Code::ConflictingFields,
        format!("give either `{a}` or `{b}`, not both"),
    )
    .label_opt(b_at, b)
    .label_opt(a_at, a)
    .help("they give the same size; keep the one you measured")
}

/// A bolt circle is given where one shape (`what`) is expected.
pub fn bolt_circle_not_shape(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedShape,
        format!("{what} must be one 2-D shape; a bolt circle is several holes"),
    )
    .label(at, "a bolt circle")
    .help("list it among a region's holes: `region(outline = …, holes = [bolt_circle(circle(diameter = 12 mm), count = 6, diameter = 85 mm)])`")
}

/// A name where a shape (`what`) goes that is no profile or section
/// (`close`: a declared one it may be a typo of).
pub fn named_shape(what: &str, name: &str, at: Span, close: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(
        Code::ExpectedShape,
        format!("{what} must be a 2-D shape; `{name}` is no profile or section"),
    )
    .label(at, format!("the name `{name}`"));
    match close {
        Some(s) => d.help(format!("did you mean `{s}`? A profile or section is taken by its name wherever a shape goes (`profile NAME = …`, `section NAME = …`)")),
        None => d.help(format!(
            "declare it (`profile {name} = outline(…)` or `section {name} = circle(…)`), or write the shape itself here (e.g. `circle(diameter = 20 mm)`)"
        )),
    }
}

/// A profile or section is placed inside itself, directly or through
/// others (`profile a = place(a, …)`).
pub fn shape_cycle(name: &str, at: Span, decl: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Cycle,
        format!("the shape `{name}` is placed inside itself"),
    )
    .label(at, format!("`{name}` here, inside its own shape"))
    .label(decl, "declared here")
    .help("a shape can hold others by name, not itself: write the inner shape out, or name a shape declared without this one")
}

/// Shapes named inside shapes write out more than `max` expression nodes.
pub fn shapes_too_large(max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooLarge,
        format!("the shapes named inside shapes here write out more than {max} pieces"),
    )
    .label(at, "written out from here on")
    .help("name each shape once where it is used: copies of copies grow with every level (three holes of a region of three holes …)")
}

/// Something that is no 2-D shape is given where one (`what`) is expected.
pub fn not_a_shape(what: &str, got: Got<'_>, at: Span, sections: &[&str]) -> Diagnostic {
    Diagnostic::error(Code::ExpectedShape, format!("{what} must be a 2-D shape"))
        .label(at, format!("this is {}", got.describe()))
        .help(format!(
            "write `outline([x, y], [x, y], arc(to = [x, y], radius = r), …)`, `region(outline = …, holes = […])`, `place(…)` or a section shape: {}",
            sections.join(", ")
        ))
}

/// An outline has more than `max` pieces.
pub fn too_many_pieces(max: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("an outline has at most {max} pieces"),
    )
    .label(at, "outline")
}

/// A piece of an outline is given a name.
pub fn named_piece(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Argument, "the pieces of an outline have no names")
        .label(at, "drop the name")
        .help("write `outline([0 mm, 0 mm], [40 mm, 0 mm], …)`")
}

/// A piece of an outline is neither a point nor an arc (`first`: it is the
/// first piece, which must be a point).
pub fn bad_piece(first: bool, got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedPoint,
        if first {
            "an outline starts with a point `[x, y]`".to_string()
        } else {
            "a piece of an outline is a point `[x, y]` or `arc(…)`".to_string()
        },
    )
    .label(at, format!("this is {}", got.describe()))
    .help("e.g. `outline([0 mm, 0 mm], [40 mm, 0 mm], arc(to = [40 mm, 20 mm], radius = 10 mm), [0 mm, 20 mm])`")
}

/// A piece of an outline ends where the one before it does.
pub fn zero_length_piece(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Degenerate, "this piece of the outline has no length")
        .label(at, "same point as the one before")
        .help("drop the repeated point")
}

/// An arc's radius is smaller than half the distance it spans.
pub fn arc_too_small(radius: Length, chord: Length, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::Degenerate,
        format!("an arc of radius {radius} cannot join points {chord} apart"),
    )
    .label(at, "radius smaller than half the chord")
    .help(format!(
        "use a radius of at least {}",
        Length(chord.0 / 2.0)
    ))
}

/// An outline of straight pieces whose corners all lie on one line.
pub fn no_area(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Degenerate, "this outline encloses no area: its corners lie on one line")
        .label(at, "outline")
        .help("an outline goes round the area it bounds: give it corners off that line, e.g. `outline([0 mm, 0 mm], [60 mm, 0 mm], [60 mm, 20 mm], [0 mm, 20 mm])`")
}

/// An outline has fewer than three corners and no arc.
pub fn too_few_corners(at: Span) -> Diagnostic {
    Diagnostic::error(Code::Degenerate, "an outline needs at least three corners")
        .label(at, "encloses no area")
        .help("give at least three points, or two points and an arc")
}

/// A point is not a list of two values.
pub fn not_a_point(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(Code::ExpectedPoint, "a point is `[x, y]`, two lengths")
        .label(at, format!("this is {}", got.describe()))
        .help("e.g. `[40 mm, 0 mm]`")
}

/// A shape that must be one outline (`what`) is a region with holes.
pub fn holes_in_hole(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(Code::ExpectedShape, format!("{what} cannot have holes of its own"))
        .label(at, "a region")
        .help("list every hole in the one region's `holes`; a hole inside a hole would be an island, built as a part of its own")
}

/// A region's `holes` is not a list.
pub fn holes_not_list(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(Code::ExpectedShape, "`holes` is a list of shapes")
        .label(at, format!("this is {}", got.describe()))
        .help("write `holes = [circle(diameter = 50 mm), place(circle(diameter = 12 mm), at = [42.5 mm, 0 mm])]`")
}

/// A region has `count` holes, more than `max`.
pub fn too_many_holes(max: usize, count: usize, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::TooManyPoints,
        format!("a region has at most {max} holes, not {count}"),
    )
    .label(at, "holes")
}

/// A loft's superellipse morph is asked for ends it cannot join.
pub fn superellipse_ends(at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BadChoice,
        "a superellipse morph needs circle, ellipse, square or rectangle ends",
    )
    .label(at, "superellipse")
    .help("use `morph = radial` for polygons and rounded rectangles")
}

/// A loft's section is too small to inset by half the bead `width`.
pub fn section_too_small(width: Length, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::SectionTooSmall,
        format!("this section is too small for a {width} wide bead measured at its outer face"),
    )
    .label(at, "section")
    .help("make the section larger or use `size = centre`")
}

/// A loft's end is neither a section's name nor a section shape.
pub fn expected_section(got: Got<'_>, at: Span, sections: &[&str]) -> Diagnostic {
    Diagnostic::error(Code::ExpectedShape, "expected a section")
        .label(at, format!("this is {}", got.describe()))
        .help(format!(
            "name a declared section or write one of: {}",
            sections.join(", ")
        ))
}

/// A loft's spine bends more than 270°.
pub fn bend_too_far(angle: Angle, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::BendAngle,
        "a bend angle above 270° makes the part collide with itself",
    )
    .label(at, format!("this is {angle}"))
    .help("bend angles up to 270° are supported")
}

/// A loft's spine is neither a line nor an arc.
pub fn not_a_spine(got: Got<'_>, at: Span) -> Diagnostic {
    Diagnostic::error(
        Code::ExpectedShape,
        "a spine is `line(length = …)` or `arc(radius = …, angle = …)`",
    )
    .label(at, format!("this is {}", got.describe()))
    .help("e.g. `spine = arc(radius = 250 mm, angle = 45 deg)`")
}
