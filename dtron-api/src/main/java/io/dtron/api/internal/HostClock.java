package io.dtron.api.internal;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * Not API. The id of the wall clock this process reads: members whose ids are equal read one and the same clock
 * (the kernel's {@code CLOCK_REALTIME} of one running Linux kernel, named by its boot id; containers on one host share
 * it), so that their clock offset is 0 and needs no estimate.
 */
public final class HostClock {
    private static final Path BOOT_ID = Path.of("/proc/sys/kernel/random/boot_id");
    private static final String ID = read(BOOT_ID);

    private HostClock() {
    }

    /** Returns this host's clock id, or "" where it cannot be told (not Linux). */
    public static String id() {
        return ID;
    }

    /** The id named by a boot-id file: "linux-boot:" and the id, or "" if it cannot be read or is blank. */
    static String read(Path bootId) {
        try {
            String id = Files.readString(bootId, StandardCharsets.US_ASCII).strip();
            return id.isEmpty() ? "" : "linux-boot:" + id;
        } catch (IOException | RuntimeException e) {
            return "";
        }
    }
}
