// placeholder until the module's first source lands; delete when adding real sources.
