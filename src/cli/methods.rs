//! `cullproof methods`: the culling methods under test, as a table or JSON.

use anyhow::Result;

/// Arguments of `cullproof methods`.
#[derive(clap::Args)]
pub struct MethodsArgs {
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Run `cullproof methods`.
pub fn run(args: MethodsArgs) -> Result<()> {
    let MethodsArgs { json } = args;
    let ms: Vec<_> = crate::bounds::registry().iter().map(|m| *m.info()).collect();
    if json {
        println!("{}", serde_json::to_string_pretty(&ms)?);
    } else {
        print!("{}", crate::bounds::render_methods(&ms));
    }
    Ok(())
}
