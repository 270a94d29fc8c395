//! The handout's printed examples: `Interpolate` (section 3) and
//! `ComputePolygonRows` (section 4), exactly.

use rasterlab::app::rows_text;
use rasterlab::{interpolate, Pixel};
use std::process::Command;

#[test]
fn interpolate_section_3_example() {
    // (4,2) to (1,8) in 4 steps gives (4,2), (3,4), (2,6), (1,8).
    let mut result = [Pixel::at(0, 0); 4];
    interpolate(Pixel::at(4, 2), Pixel::at(1, 8), &mut result);
    assert_eq!(
        result,
        [
            Pixel::at(4, 2),
            Pixel::at(3, 4),
            Pixel::at(2, 6),
            Pixel::at(1, 8)
        ]
    );
}

const HANDOUT_ROWS: &str = "\
Start: (10,5). End: (10,5). 
Start: (9,6). End: (10,6). 
Start: (8,7). End: (11,7). 
Start: (7,8). End: (11,8). 
Start: (6,9). End: (12,9). 
Start: (5,10). End: (12,10). 
Start: (7,11). End: (13,11). 
Start: (9,12). End: (13,12). 
Start: (11,13). End: (14,13). 
Start: (13,14). End: (14,14). 
Start: (15,15). End: (15,15). 
";

#[test]
fn compute_polygon_rows_section_4_example() {
    assert_eq!(rows_text(&[(10, 5), (5, 10), (15, 15)]), HANDOUT_ROWS);
}

#[test]
fn rows_subcommand_prints_the_handouts_output() {
    let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["rows", "10,5", "5,10", "15,15"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(String::from_utf8(out.stdout).unwrap(), HANDOUT_ROWS);
}

#[test]
fn a_single_point_is_one_row() {
    assert_eq!(rows_text(&[(3, 7)]), "Start: (3,7). End: (3,7). \n");
}

#[test]
fn a_horizontal_segment_is_one_row_from_its_left_end_to_its_right_end() {
    let expected = "Start: (2,4). End: (9,4). \n";
    assert_eq!(rows_text(&[(9, 4), (2, 4)]), expected);
    assert_eq!(rows_text(&[(2, 4), (9, 4)]), expected);
}

#[test]
fn a_vertical_segment_is_one_pixel_per_row() {
    assert_eq!(
        rows_text(&[(5, -1), (5, 2)]),
        "Start: (5,-1). End: (5,-1). \n\
         Start: (5,0). End: (5,0). \n\
         Start: (5,1). End: (5,1). \n\
         Start: (5,2). End: (5,2). \n"
    );
}

#[test]
fn a_quadrilateral() {
    // A diamond: rows widen by 2 per row, then narrow. Worked by hand: the edges
    // (3,0)-(6,3)-(3,6)-(0,3) step one pixel in x per row.
    let expected = "\
Start: (3,0). End: (3,0). 
Start: (2,1). End: (4,1). 
Start: (1,2). End: (5,2). 
Start: (0,3). End: (6,3). 
Start: (1,4). End: (5,4). 
Start: (2,5). End: (4,5). 
Start: (3,6). End: (3,6). 
";
    assert_eq!(rows_text(&[(3, 0), (6, 3), (3, 6), (0, 3)]), expected);
}

#[test]
fn a_pentagon_has_rows_only_between_its_extremes() {
    // A house: square (0,2)-(4,2)-(4,5)-(0,5) under a roof peak at (2,0).
    let expected = "\
Start: (2,0). End: (2,0). 
Start: (1,1). End: (3,1). 
Start: (0,2). End: (4,2). 
Start: (0,3). End: (4,3). 
Start: (0,4). End: (4,4). 
Start: (0,5). End: (4,5). 
";
    assert_eq!(
        rows_text(&[(2, 0), (4, 2), (4, 5), (0, 5), (0, 2)]),
        expected
    );
}

#[test]
fn winding_does_not_change_the_rows() {
    let cw = rows_text(&[(10, 5), (5, 10), (15, 15)]);
    let ccw = rows_text(&[(15, 15), (5, 10), (10, 5)]);
    assert_eq!(cw, ccw);
    let quad = [(3, 0), (6, 3), (3, 6), (0, 3)];
    let mut reversed = quad;
    reversed.reverse();
    assert_eq!(rows_text(&quad), rows_text(&reversed));
}
