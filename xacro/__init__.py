"""Package data: the xacro templates of the registered mechanisms, read with `importlib.resources`."""
