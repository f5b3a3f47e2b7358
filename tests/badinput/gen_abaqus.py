"""Placeholder until the Abaqus corpus is written."""


def cases():
    return iter(())
