package io.dtron.xta;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.stream.Stream;

/** The real Uppaal models in {@code ../shared/models}, written by others (a test helper, shared with xtaapi). */
public final class SharedModels {
    private SharedModels() {
    }

    /** The models folder. */
    public static Path root() {
        String configured = System.getProperty("dtron.shared");
        Path base = configured != null ? Path.of(configured) : Path.of("..", "..", "shared");
        Path models = base.resolve("models").normalize();
        if (!Files.isDirectory(models)) {
            throw new IllegalStateException("shared models not found at " + models.toAbsolutePath());
        }
        return models;
    }

    /** Every .xml, .xta and .ta file, sorted. */
    public static List<Path> modelFiles() {
        try (Stream<Path> files = Files.walk(root())) {
            return files.filter(Files::isRegularFile)
                    .filter(p -> p.toString().matches(".*\\.(xml|xta|ta)$"))
                    .sorted()
                    .toList();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** The decoded text of a model file. */
    public static String read(Path file) {
        try {
            return ModelSyntax.decode(Files.readAllBytes(file));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
