package io.dtron.xta;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.stream.Stream;

/** The real Uppaal models in {@code ../shared/models}, written by others. */
final class SharedModels {
    private SharedModels() {
    }

    static Path root() {
        String configured = System.getProperty("dtron.shared");
        Path base = configured != null ? Path.of(configured) : Path.of("..", "..", "shared");
        Path models = base.resolve("models").normalize();
        if (!Files.isDirectory(models)) {
            throw new IllegalStateException("shared models not found at " + models.toAbsolutePath());
        }
        return models;
    }

    static List<Path> modelFiles() {
        try (Stream<Path> files = Files.walk(root())) {
            return files.filter(Files::isRegularFile)
                    .filter(p -> p.toString().matches(".*\\.(xml|xta|ta)$"))
                    .sorted()
                    .toList();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    static String read(Path file) {
        try {
            return ModelSyntax.decode(Files.readAllBytes(file));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
