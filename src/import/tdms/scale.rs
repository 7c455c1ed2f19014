//! Linear scales in channel properties (`NI_Scale[n]_...`), applied as npTDMS applies them.

use super::{Object, Property};

/// Scale input source meaning the raw data.
pub(super) const SOURCE_RAW: u64 = 0xFFFF_FFFF;
/// An object's linear scales as a chain to apply first to last, `None` when it has no scales
/// (or says its data is already scaled).
pub(super) fn linear_scales(o: &Object) -> Result<Option<Vec<(f64, f64)>>, String> {
    let declared = o.property("NI_Number_Of_Scales").and_then(Property::as_f64);
    let typed = o
        .properties
        .iter()
        .filter_map(|(n, _)| scale_index(n))
        .max()
        .map(|m| m as f64 + 1.0);
    let Some(count) = declared.or(typed).filter(|&n| n >= 1.0) else {
        return Ok(None);
    };
    if matches!(o.property("NI_Scaling_Status"), Some(Property::Text(s)) if s == "scaled") {
        return Ok(None);
    }
    // Each scale needs a type property: a count beyond the properties there is garbage.
    if count > o.properties.len() as f64 {
        return Err(format!(
            "NI_Number_Of_Scales is {count}, more than the channel's {} properties",
            o.properties.len()
        ));
    }
    let count = count as u64;
    let mut chain = Vec::new();
    let mut scale = count - 1;
    loop {
        if chain.len() as u64 >= count {
            return Err("its scales' input sources form a loop".into());
        }
        let key = |what: &str| format!("NI_Scale[{scale}]_{what}");
        match o.property(&key("Scale_Type")) {
            Some(Property::Text(t)) if t == "Linear" => {}
            Some(Property::Text(t)) => {
                return Err(format!(
                    "scale {scale} is of type {t:?}; dlw applies Linear scales only (export scaled data)"
                ))
            }
            _ => {
                return Err(format!(
                    "scale {scale} has no NI_Scale[{scale}]_Scale_Type (a DAQmx scaler?); export scaled data"
                ))
            }
        }
        let number = |what: &str| {
            o.property(&key(what))
                .and_then(Property::as_f64)
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("scale {scale} has no finite {}", key(what)))
        };
        chain.push((number("Linear_Slope")?, number("Linear_Y_Intercept")?));
        let source = o
            .property(&key("Linear_Input_Source"))
            .and_then(Property::as_f64)
            .map_or(SOURCE_RAW, |v| v as u64);
        if source == SOURCE_RAW {
            break;
        }
        if source >= count {
            return Err(format!(
                "scale {scale}'s input source {source} is not one of its {count} scales"
            ));
        }
        scale = source;
    }
    chain.reverse();
    Ok(Some(chain))
}

/// `n` of a property named `NI_Scale[n]_Scale_Type`.
pub(super) fn scale_index(name: &str) -> Option<u64> {
    name.strip_prefix("NI_Scale[")?
        .strip_suffix("]_Scale_Type")?
        .parse()
        .ok()
}
