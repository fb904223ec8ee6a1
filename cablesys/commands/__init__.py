"""The sub-commands that run a scene through every layer (``run``, ``scene``): above the analyses and the
model ladder they call, so that no analysis package depends on the ladder."""
