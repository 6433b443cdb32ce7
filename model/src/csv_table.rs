//! Embedded reference tables (CSV files in `model/data`, each with its `#` provenance header).
//!
//! The tables are compiled into the binary so the model never touches the file system; each is
//! parsed once on first use. Parsing cannot fail at run time for a table that passed the tests,
//! so a malformed embedded table is a build defect and panics with the table's name.

use std::collections::HashMap;

/// A parsed CSV table: named columns of text cells.
#[derive(Debug, Clone)]
pub struct Table {
    name: &'static str,
    columns: HashMap<String, usize>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// Parses a CSV text whose leading `#` lines are provenance comments and whose first
    /// non-comment line names the columns. Quoted cells may contain commas.
    pub fn parse(name: &'static str, text: &str) -> Table {
        let mut lines = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'));
        let header = lines
            .next()
            .unwrap_or_else(|| panic!("embedded table {name} has no header"));
        let columns = split_csv(header)
            .into_iter()
            .enumerate()
            .map(|(i, c)| (c, i))
            .collect::<HashMap<_, _>>();
        let rows = lines.map(split_csv).collect::<Vec<_>>();
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(
                row.len(),
                columns.len(),
                "embedded table {name}: row {i} has {} cells, header has {}",
                row.len(),
                columns.len()
            );
        }
        Table {
            name,
            columns,
            rows,
        }
    }

    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    fn index(&self, column: &str) -> usize {
        *self
            .columns
            .get(column)
            .unwrap_or_else(|| panic!("embedded table {} has no column {column}", self.name))
    }

    /// The text cells of one column.
    pub fn text(&self, column: &str) -> Vec<&str> {
        let i = self.index(column);
        self.rows.iter().map(|r| r[i].as_str()).collect()
    }

    /// One column as numbers.
    pub fn numbers(&self, column: &str) -> Vec<f64> {
        let i = self.index(column);
        self.rows
            .iter()
            .enumerate()
            .map(|(k, r)| {
                r[i].parse::<f64>().unwrap_or_else(|_| {
                    panic!(
                        "embedded table {}: row {k} column {column} is not a number: {:?}",
                        self.name, r[i]
                    )
                })
            })
            .collect()
    }

    /// The rows whose `column` equals `value`, as a new table with the same columns.
    pub fn filter(&self, column: &str, value: &str) -> Table {
        let i = self.index(column);
        Table {
            name: self.name,
            columns: self.columns.clone(),
            rows: self
                .rows
                .iter()
                .filter(|r| r[i] == value)
                .cloned()
                .collect(),
        }
    }
}

fn split_csv(line: &str) -> Vec<String> {
    let mut cells = Vec::new();
    let mut cell = String::new();
    let mut quoted = false;
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => cells.push(std::mem::take(&mut cell)),
            _ => cell.push(ch),
        }
    }
    cells.push(cell);
    cells.into_iter().map(|c| c.trim().to_string()).collect()
}

/// Declares a lazily parsed embedded table.
macro_rules! embedded_table {
    ($fn_name:ident, $file:literal) => {
        pub fn $fn_name() -> &'static $crate::csv_table::Table {
            static TABLE: std::sync::OnceLock<$crate::csv_table::Table> =
                std::sync::OnceLock::new();
            TABLE.get_or_init(|| {
                $crate::csv_table::Table::parse($file, include_str!(concat!("../data/", $file)))
            })
        }
    };
}

/// Every embedded table, by file name.
pub mod tables {
    embedded_table!(cie1931_2deg, "cie1931_2deg_cmf_1nm.csv");
    embedded_table!(cie_d65, "cie_d65_spd_5nm.csv");
    embedded_table!(solar_astm_g173, "solar_etr_astm_g173.csv");
    embedded_table!(solar_gueymard2004, "solar_etr_gueymard2004.csv");
    embedded_table!(solar_bruneton_10nm, "solar_etr_bruneton_10nm.csv");
    embedded_table!(solar_wehrli1985, "solar_etr_skytracer_wehrli1985.csv");
    embedded_table!(ozone_bogumil2003, "ozone_xsec_bogumil2003_1nm.csv");
    embedded_table!(ozone_serdyuchenko_233k, "ozone_xsec_bruneton_233K_10nm.csv");
    embedded_table!(ozone_monthly_arosa, "ozone_monthly_total_column_arosa.csv");
    embedded_table!(
        ozone_guimera_layers,
        "ozone_vertical_distribution_guimera.csv"
    );
    embedded_table!(
        rayleigh_bucholtz1995,
        "rayleigh_bucholtz1995_beta_standard_air.csv"
    );
    embedded_table!(rayleigh_air_derived, "rayleigh_air_derived_1nm.csv");
    embedded_table!(us_standard_1976, "us_standard_atmosphere_1976.csv");
    embedded_table!(afgl1986, "afgl1986_atmospheres.csv");
    embedded_table!(
        opac_size_distributions,
        "opac_component_size_distributions.csv"
    );
    embedded_table!(opac_refractive_indices, "opac_refractive_indices.csv");
    embedded_table!(opac_type_profiles, "opac_type_profiles_libradtran.csv");
    embedded_table!(guimera_aerosol_types, "aerosol_guimera2018_type_params.csv");
    embedded_table!(garcia_linan_constants, "garcia_linan_2023_constants.csv");
    embedded_table!(garcia_linan_refit, "garcia_linan_refit.csv");
    embedded_table!(spectral4_fitted, "spectral4_fitted.csv");
    embedded_table!(preetham_constants, "preetham1999_constants.csv");
    embedded_table!(hillaire_earth, "hillaire2020_earth_defaults.csv");
    embedded_table!(cie_standard_general_sky, "cie2003_standard_general_sky.csv");
    embedded_table!(
        hosek_wilkie_sky_spectral,
        "hosek_wilkie2012_sky_spectral.csv"
    );
    embedded_table!(hosek_wilkie_sky_rgb, "hosek_wilkie2012_sky_rgb.csv");
    embedded_table!(hosek_wilkie_sun, "hosek_wilkie2013_sun.csv");
    embedded_table!(
        hosek_wilkie_limb_darkening,
        "hosek_wilkie2013_limb_darkening.csv"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_embedded_table_parses_with_rows() {
        let all = [
            tables::cie1931_2deg(),
            tables::cie_d65(),
            tables::solar_astm_g173(),
            tables::solar_gueymard2004(),
            tables::solar_bruneton_10nm(),
            tables::solar_wehrli1985(),
            tables::ozone_bogumil2003(),
            tables::ozone_serdyuchenko_233k(),
            tables::ozone_monthly_arosa(),
            tables::ozone_guimera_layers(),
            tables::rayleigh_bucholtz1995(),
            tables::rayleigh_air_derived(),
            tables::us_standard_1976(),
            tables::afgl1986(),
            tables::opac_size_distributions(),
            tables::opac_refractive_indices(),
            tables::opac_type_profiles(),
            tables::guimera_aerosol_types(),
            tables::garcia_linan_constants(),
            tables::spectral4_fitted(),
            tables::preetham_constants(),
            tables::hillaire_earth(),
            tables::cie_standard_general_sky(),
            tables::hosek_wilkie_sky_spectral(),
            tables::hosek_wilkie_sky_rgb(),
            tables::hosek_wilkie_sun(),
            tables::hosek_wilkie_limb_darkening(),
        ];
        assert_eq!(tables::garcia_linan_refit().len(), 4);
        for t in all {
            assert!(t.len() >= 6, "table {} has only {} rows", t.name, t.len());
        }
        assert_eq!(tables::cie1931_2deg().len(), 471);
        assert_eq!(tables::ozone_monthly_arosa().len(), 12);
        assert_eq!(tables::afgl1986().len(), 300);
    }

    #[test]
    fn quoted_cells_keep_their_commas() {
        assert_eq!(split_csv(r#"a,"b, c",d"#), vec!["a", "b, c", "d"]);
    }
}
