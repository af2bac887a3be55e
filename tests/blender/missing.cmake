# A test whose tool is missing fails with what to do, instead of skipping silently.
message(FATAL_ERROR "${WHAT} not found: the Blender add-on's tests need it; run scripts/install-deps.sh "
                    "(it installs Debian's blender and python3), then configure again")
