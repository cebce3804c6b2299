package io.dtron.junit.internal;

import java.io.IOException;
import java.io.Reader;
import java.io.UncheckedIOException;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Properties;
import java.util.Set;

/**
 * The seeds of the runs that did not pass, per test method ({@code CLASS#METHOD}), in a properties file: a seed is
 * stored when its run fails and taken out when it passes, so that it runs first until it passes. Safe for the
 * tests of one JVM that run at once; the file is replaced as a whole.
 */
final class SeedStore {
    private static final Object LOCK = new Object();
    private final Path file;

    SeedStore(Path file) {
        this.file = file;
    }

    Path file() {
        return file;
    }

    /** The stored seeds of {@code key}, in the order they failed. */
    List<Long> failed(String key) {
        synchronized (LOCK) {
            List<Long> seeds = new ArrayList<>();
            String value = read().getProperty(key, "");
            for (String s : value.split(",")) {
                if (!s.isBlank()) {
                    try {
                        seeds.add(Long.parseLong(s.strip()));
                    } catch (NumberFormatException e) {
                        // a hand-edited entry that is no seed: ignored, and dropped when the key is written again
                    }
                }
            }
            return seeds;
        }
    }

    /** Stores {@code seed} for {@code key} when its run did not pass, takes it out when it did. */
    void record(String key, long seed, boolean passed) {
        synchronized (LOCK) {
            Set<Long> seeds = new LinkedHashSet<>(failed(key));
            boolean changed = passed ? seeds.remove(seed) : seeds.add(seed);
            if (!changed) {
                return;
            }
            Properties all = read();
            if (seeds.isEmpty()) {
                all.remove(key);
            } else {
                all.setProperty(key, String.join(",", seeds.stream().map(String::valueOf).toList()));
            }
            write(all);
        }
    }

    private Properties read() {
        Properties properties = new Properties();
        if (Files.isRegularFile(file)) {
            try (Reader in = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
                properties.load(in);
            } catch (IOException | IllegalArgumentException e) {
                throw new IllegalStateException("cannot read the failed seeds of DTRON's tests from " + file + ": "
                        + e.getMessage() + " (delete the file to start afresh)", e);
            }
        }
        return properties;
    }

    private void write(Properties properties) {
        try {
            Path folder = file.toAbsolutePath().getParent();
            Files.createDirectories(folder);
            Path temporary = Files.createTempFile(folder, file.getFileName().toString(), ".tmp");
            try (Writer out = Files.newBufferedWriter(temporary, StandardCharsets.UTF_8)) {
                properties.store(out, "seeds of DTRON runs that did not pass: they run first next time");
            }
            Files.move(temporary, file, StandardCopyOption.REPLACE_EXISTING, StandardCopyOption.ATOMIC_MOVE);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot store the failed seed in " + file + ": " + e.getMessage(), e);
        }
    }
}
