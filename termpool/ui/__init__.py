"""Terminal user interface: half-block pixel canvas, diffed screen output, table drawing."""
