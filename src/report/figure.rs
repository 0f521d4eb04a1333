//! What the page shows: figures (an SVG with a caption and the plotted numbers) in sections.

/// The numbers behind a figure, shown in a collapsible table under it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ValueTable {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// One figure of the page.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// An `<svg>` element (plots, maps), or `None` for a table-only entry.
    pub svg: Option<String>,
    pub caption: String,
    pub values: Option<ValueTable>,
}

/// A titled group of figures with an introduction.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Section {
    pub title: String,
    pub intro: String,
    pub figures: Vec<Figure>,
}
