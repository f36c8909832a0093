//! ARCHITECTURE.md's table "Where to look: questions and files" keeps
//! pointing at files that exist (issue 27): every path in its second column
//! is a file of the repository.

use std::path::Path;

#[test]
fn every_file_the_question_table_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
    let start = text
        .find("### Where to look: questions and files")
        .expect("ARCHITECTURE.md has the question table");
    let rows: Vec<&str> = text[start..]
        .lines()
        .skip_while(|l| !l.starts_with("| question"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .collect();
    assert!(rows.len() >= 10, "the table has {} rows", rows.len());
    let mut asked = Vec::new();
    for row in rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (question, file) = (cells[1], cells[2].trim_matches('`'));
        assert!(
            root.join(file).is_file(),
            "ARCHITECTURE.md: \"{question}\" points at {file}, which does not exist"
        );
        asked.push(question.to_lowercase());
    }
    for must in ["penetration depth", "motion certified"] {
        assert!(
            asked.iter().any(|q| q.contains(must)),
            "the table must answer a question about {must}"
        );
    }
}
