package io.dtron.cli;

import io.dtron.engine.control.ModelVersion;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.ClosedWatchServiceException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardWatchEventKinds;
import java.nio.file.WatchKey;
import java.nio.file.WatchService;
import java.util.ArrayList;
import java.util.List;

/**
 * The file of new model versions of {@code dtron control --reload-from}: loaded and checked ({@link
 * ModelVersion#check}) when the run starts and whenever the file is written (best moved into place whole), each
 * outcome handed to a {@link Sink}. A version is checked with the queries of the {@code .q} file beside it, else those
 * written in it, else those of the {@code .q} file beside the model the run started with.
 */
final class ModelVersionFile implements AutoCloseable {
    /** Where the outcomes go; called on the watching thread. */
    interface Sink {
        /** The version loaded and was checked: accepted or refused. */
        void checked(ModelVersion.Check check);

        /** The version (its file name) does not load, or its queries cannot be read, for {@code reason}. */
        void unloadable(String version, String reason);
    }

    private final Path file;
    private final String label;
    private final Path started;
    private final Path interfaceFile;
    private final TestInterface running;
    private final Sink sink;
    private WatchService service;

    /**
     * Versions in {@code file} of the model {@code started} (whose interface is {@code running}), with the interface
     * file {@code interfaceFile} when the run has one (else null: the i_/o_ names).
     */
    ModelVersionFile(Path file, Path started, Path interfaceFile, TestInterface running, Sink sink) {
        this.file = file.toAbsolutePath();
        this.label = file.toString();
        this.started = started;
        this.interfaceFile = interfaceFile;
        this.running = running;
        this.sink = sink;
    }

    /** Checks the file as it is now, if it exists. */
    void checkNow() {
        if (Files.exists(file)) {
            check();
        }
    }

    /** Checks the file whenever it is written or moved into place, on a daemon thread, until {@link #close}. */
    void watch() {
        try {
            service = file.getFileSystem().newWatchService();
            file.getParent().register(service, StandardWatchEventKinds.ENTRY_CREATE,
                    StandardWatchEventKinds.ENTRY_MODIFY);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot watch " + label + ": " + e.getMessage(), e);
        }
        Thread thread = new Thread(this::watching, "dtron-model-versions");
        thread.setDaemon(true);
        thread.start();
    }

    private void watching() {
        try {
            while (true) {
                WatchKey key = service.take();
                boolean ours = key.pollEvents().stream().anyMatch(e -> e.context() instanceof Path p
                        && file.getFileName().equals(p));
                key.reset();
                if (ours && Files.exists(file)) {
                    check();
                }
            }
        } catch (InterruptedException | ClosedWatchServiceException e) {
            // closed: the run is over
        }
    }

    private void check() {
        Path own = beside(file);
        String ownQueries;
        try {
            ownQueries = Files.isRegularFile(own) ? Files.readString(own, StandardCharsets.UTF_8) : null;
        } catch (IOException e) {
            sink.unloadable(label, "its queries cannot be read: " + e.getMessage());
            return;
        }
        check(label, () -> ModelLoader.load(file), ownQueries, started, interfaceFile, running, sink);
    }

    /** Loads a model version; a {@link ModelException} when it does not load. */
    interface Loader {
        Network load() throws ModelException;
    }

    /**
     * Loads the version {@code label} and checks it against the running interface {@code running} (the i_/o_ names,
     * or {@code interfaceFile}'s), with the queries {@code ownQueries} (the text of its {@code .q}; null when it has
     * none: then those written in it, else those of the {@code .q} beside the model {@code started} with), and hands
     * the outcome to {@code sink}.
     */
    static void check(String label, Loader loader, String ownQueries, Path started, Path interfaceFile,
            TestInterface running, Sink sink) {
        Network network;
        TestInterface testInterface;
        List<Query> queries;
        try {
            network = loader.load();
            testInterface = CommandModel.interfaceOf(network, interfaceFile);
            queries = ownQueries != null ? Query.parseFile(ownQueries) : queriesFor(network, started);
        } catch (ModelException e) {
            sink.unloadable(label, "it does not load: " + e.getMessage().lines().findFirst().orElse(""));
            return;
        } catch (IOException e) {
            sink.unloadable(label, "its queries cannot be read: " + e.getMessage());
            return;
        }
        sink.checked(ModelVersion.check(new ModelVersion(label, network, testInterface), running, queries));
    }

    private static List<Query> queriesFor(Network network, Path started) throws IOException {
        if (!network.queries().isEmpty()) {
            List<Query> written = new ArrayList<>();
            for (io.dtron.xta.ast.Query q : network.queries()) {
                try {
                    written.add(Query.parse(q.pos().text()));
                } catch (QueryException e) {
                    written.add(new Query(q.pos().text().strip(), Query.Kind.INVALID, null, null, e.getMessage(), 0,
                            0));
                }
            }
            return written;
        }
        Path first = beside(started);
        return Files.isRegularFile(first) ? Query.parseFile(Files.readString(first, StandardCharsets.UTF_8))
                : List.of();
    }

    /** {@code FILE.q} for {@code FILE.xta} (or .xml, .ta). */
    static Path beside(Path model) {
        String name = model.getFileName().toString();
        int dot = name.lastIndexOf('.');
        return model.resolveSibling((dot > 0 ? name.substring(0, dot) : name) + ".q");
    }

    @Override
    public void close() {
        if (service != null) {
            try {
                service.close();
            } catch (IOException e) {
                // closing: nothing to do
            }
        }
    }
}
