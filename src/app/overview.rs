//! Figure 1: every stage's figure side by side, each labelled, so the steps can be
//! compared at a glance. Four columns in the handout's order; the eighth panel is
//! what perspective correction changes, Figure 7 against Figure 8 as a heat map.

use crate::app::figure::Figure;
use crate::measure::heat::{heat_map, HEAT_FULL_SCALE};
use crate::measure::plot::Canvas;
use crate::pipeline::Frame;

/// Gutter between panels, in pixels.
pub const GUTTER: u32 = 8;
/// Panels per row.
pub const COLUMNS: u32 = 4;
/// The strip under each panel that holds its label.
pub const LABEL_HEIGHT: u32 = 28;
const BACKGROUND: u32 = 0x0040_4040;
const LABEL: u32 = 0x00ff_ffff;

/// One panel: an image and the words under it.
pub struct Panel {
    pub frame: Frame,
    pub label: String,
}

/// Figure 1 from Figures 2 to 8, in [`Figure::FIGURES`] order, taken as they
/// are (their colours; no copy of them is made). Refused, saying why, if there
/// are not seven of them, their sizes differ or the memory cannot be had.
pub fn figure_one(figures: Vec<Frame>) -> Result<Frame, String> {
    if figures.len() != Figure::FIGURES.len() {
        return Err(format!("{} figures, not seven", figures.len()));
    }
    let heat = heat_map(&figures[5], &figures[6])?;
    let mut panels: Vec<Panel> = figures
        .into_iter()
        .zip(Figure::FIGURES)
        .enumerate()
        .map(|(i, (frame, figure))| Panel {
            frame,
            label: format!("Figure {}: {}", i + 2, figure.label()),
        })
        .collect();
    // Single pixels vanish when the overview is shown small: points as 3 x 3 dots.
    panels[0].frame = dilate(&panels[0].frame)?;
    panels.push(Panel {
        frame: heat,
        label: format!("7 vs 8: white = {HEAT_FULL_SCALE}+ apart"),
    });
    grid(&panels)
}

/// Lays out same-sized panels in a grid, each with its label beneath; refused,
/// saying why, if their sizes differ or the memory cannot be had.
pub fn grid(panels: &[Panel]) -> Result<Frame, String> {
    let Some(first) = panels.first() else {
        return Err("no panels".into());
    };
    let (fw, fh) = (first.frame.width, first.frame.height);
    if panels
        .iter()
        .any(|p| (p.frame.width, p.frame.height) != (fw, fh))
    {
        return Err("panels of different sizes".into());
    }
    let count = panels.len() as u32;
    let (cols, rows) = (count.min(COLUMNS), count.div_ceil(COLUMNS));
    let cell_h = fh + LABEL_HEIGHT;
    let width = cols * fw + (cols - 1) * GUTTER;
    let height = rows * cell_h + (rows - 1) * GUTTER;
    let mut canvas = Canvas::try_new(width, height, BACKGROUND)?;
    for (i, panel) in panels.iter().enumerate() {
        let (col, row) = (i as u32 % COLUMNS, i as u32 / COLUMNS);
        let (x0, y0) = (col * (fw + GUTTER), row * (cell_h + GUTTER));
        for y in 0..fh {
            let src = &panel.frame.color[(y * fw) as usize..][..fw as usize];
            let start = ((y0 + y) * width + x0) as usize;
            canvas.frame.color[start..start + fw as usize].copy_from_slice(src);
        }
        // Text two font pixels a dot when it fits, else one.
        let scale = if Canvas::text_width(&panel.label, 2) <= fw as i32 - 8 {
            2
        } else {
            1
        };
        let text_y = (y0 + fh) as i32 + (LABEL_HEIGHT as i32 - 8 * scale) / 2;
        canvas.text((x0 as i32 + 4, text_y), &panel.label, scale, LABEL);
    }
    Ok(canvas.frame)
}

/// Every lit pixel grown to a 3 x 3 dot.
fn dilate(frame: &Frame) -> Result<Frame, String> {
    let mut out = Frame::try_new(frame.width, frame.height, false)?;
    out.color.copy_from_slice(&frame.color);
    let (w, h) = (frame.width as i64, frame.height as i64);
    for y in 0..h {
        for x in 0..w {
            let c = frame.color[(y * w + x) as usize];
            if c == 0 {
                continue;
            }
            for (dx, dy) in (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))) {
                let (nx, ny) = (x + dx, y + dy);
                if (0..w).contains(&nx) && (0..h).contains(&ny) {
                    out.color[(ny * w + nx) as usize] = c;
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::target::unpack;

    #[test]
    fn panels_land_in_a_grid_with_their_labels() {
        let mut a = Frame::new(200, 2);
        a.color[399] = 0x00ff_0000; // bottom right of panel 0
        let mut panels = vec![Panel {
            frame: a,
            label: "I".into(),
        }];
        for _ in 0..4 {
            panels.push(Panel {
                frame: Frame::new(200, 2),
                label: String::new(),
            });
        }
        let f = grid(&panels).unwrap();
        let cell = 2 + LABEL_HEIGHT;
        assert_eq!(
            (f.width, f.height),
            (4 * 200 + 3 * GUTTER, 2 * cell + GUTTER)
        );
        assert_eq!(f.rgb(199, 1), [255, 0, 0]);
        assert_eq!(f.rgb(200, 0), unpack(BACKGROUND), "gutter");
        assert_eq!(f.rgb(0, cell + GUTTER), [0, 0, 0], "second row");
        // The label "I" is drawn in white somewhere under the first panel.
        let label_white = (2..cell).any(|y| (0..40).any(|x| f.rgb(x, y) == [255, 255, 255]));
        assert!(label_white);
        assert_eq!(grid(&[]), Err("no panels".to_string()));
    }

    #[test]
    fn points_become_dots() {
        let mut f = Frame::new(5, 5);
        f.color[12] = 0x00ff_ffff;
        let d = dilate(&f).unwrap();
        assert_eq!(d.color.iter().filter(|&&c| c != 0).count(), 9);
    }
}
