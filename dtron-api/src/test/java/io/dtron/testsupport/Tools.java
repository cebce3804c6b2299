package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.fail;

import org.junit.jupiter.api.Assumptions;

/**
 * The outside tools some tests run (nats-server, a Python with the client, CMake, jq...): a test whose tool is
 * missing is skipped, unless {@code DTRON_REQUIRE_TOOLS=1} (set by {@code scripts/test}, which installs them all)
 * says that every test must run: then it fails, naming the tool.
 */
public final class Tools {
    private Tools() {
    }

    /** Skips the calling test when {@code present} is false, or fails it under {@code DTRON_REQUIRE_TOOLS=1}. */
    public static void require(boolean present, String what) {
        if (!present && "1".equals(System.getenv("DTRON_REQUIRE_TOOLS"))) {
            fail(what + " is missing, and DTRON_REQUIRE_TOOLS=1 requires it (scripts/test installs it)");
        }
        Assumptions.assumeTrue(present, what + " is not installed: skipped (scripts/test installs it and runs this"
                + " test)");
    }
}
