//! 3MF packages written for the tests: the smallest a 3MF can be (the
//! content types, the relationship to the model, the model), which
//! `lmdc::geometry::mesh::three_mf::read` must read.

use std::io::{Cursor, Write};

/// A 3MF affine transform as the file writes it (12 numbers, row by row).
pub type Affine = [f64; 12];

/// A 3MF package of one object, `tris` (indexed by `vertices`), in `unit`
/// (its name in the file), built as the items `transforms` (`None`: no
/// transform).
pub fn package(
    vertices: &[[f64; 3]],
    tris: &[[usize; 3]],
    unit: &str,
    transforms: &[Option<Affine>],
) -> Vec<u8> {
    let mut xml = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"{unit}\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n<resources>\n<object id=\"1\" type=\"model\">\n<mesh>\n<vertices>\n"
    );
    for v in vertices {
        xml += &format!("<vertex x=\"{}\" y=\"{}\" z=\"{}\"/>\n", v[0], v[1], v[2]);
    }
    xml += "</vertices>\n<triangles>\n";
    for t in tris {
        xml += &format!(
            "<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>\n",
            t[0], t[1], t[2]
        );
    }
    xml += "</triangles>\n</mesh>\n</object>\n</resources>\n<build>\n";
    for t in transforms {
        match t {
            Some(m) => {
                let m: Vec<String> = m.iter().map(f64::to_string).collect();
                xml += &format!("<item objectid=\"1\" transform=\"{}\"/>\n", m.join(" "));
            }
            None => xml += "<item objectid=\"1\"/>\n",
        }
    }
    xml += "</build>\n</model>\n";
    zip_model(&xml)
}

/// A 3MF package whose model part is `xml`.
pub fn zip_model(xml: &str) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default();
    let parts = [
        ("[Content_Types].xml", CONTENT_TYPES),
        ("_rels/.rels", RELS),
        ("3D/3dmodel.model", xml),
    ];
    for (name, text) in parts {
        // Writing to memory cannot fail.
        let _ = zip.start_file(name, opts);
        let _ = zip.write_all(text.as_bytes());
    }
    zip.finish().map(Cursor::into_inner).unwrap_or_default()
}

const CONTENT_TYPES: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n";

const RELS: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>\n";
