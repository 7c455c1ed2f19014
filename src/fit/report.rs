//! placeholder
pub fn report_page() {}
