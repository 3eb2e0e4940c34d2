"""Scenarios shipped with amiro: the paper's hydration scenario and others."""
