use geo::{Area, BoundingRect, Rect};

use super::Layout;

impl Layout {
    /// Total designed notch area in the unrolled drawing (mm²): `N·h·s_n` (twice that for BSN)
    /// for a generated layout, whatever pieces the seam split notches into.
    pub fn notch_area_mm2(&self) -> f64 {
        self.notches
            .iter()
            .flat_map(|n| &n.outline)
            .map(|p| p.unsigned_area())
            .sum()
    }

    /// Number of sensors (1 for UAN, 2 for BSN), counted from the traces.
    pub fn sensor_count(&self) -> usize {
        self.sensors.iter().map(|t| t.sensor + 1).max().unwrap_or(0)
    }

    /// Bounding box of every feature in `(x, s)` (mm), or `None` for an empty layout.
    pub fn extents(&self) -> Option<Rect<f64>> {
        let notch_boxes = self
            .notches
            .iter()
            .flat_map(|n| &n.outline)
            .filter_map(|p| p.bounding_rect());
        let line_boxes = self
            .sensors
            .iter()
            .chain(&self.leads)
            .chain(&self.pads)
            .flat_map(|t| &t.pieces)
            .chain(&self.parting)
            .filter_map(|l| l.bounding_rect());
        notch_boxes.chain(line_boxes).reduce(|a, b| {
            Rect::new(
                geo::Coord {
                    x: a.min().x.min(b.min().x),
                    y: a.min().y.min(b.min().y),
                },
                geo::Coord {
                    x: a.max().x.max(b.max().x),
                    y: a.max().y.max(b.max().y),
                },
            )
        })
    }
}
