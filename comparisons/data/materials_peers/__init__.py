"""pyvisco's example DMA master curves and the Prony fits of pyvisco and ANSYS to them
(`comparisons.bench.materials_peers`; a package only so that the files are installed)."""
