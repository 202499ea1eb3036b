"""Reports built from leaderboards: views laid out as the papers lay out their results."""
