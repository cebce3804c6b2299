package io.dtron.model;

import io.dtron.model.internal.NetworkCompiler;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.LargeStack;
import io.dtron.xta.ModelSyntax;
import io.dtron.xta.Parsed;
import io.dtron.xta.ast.Nta;
import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/**
 * Loads Uppaal models into {@link Network}s: from files ({@code .xml} of any DTD version, {@code .xta}, old
 * {@code .ta}), strings, the classpath or a {@link ModelStore}. Every problem is reported with its file, line
 * and column; a model with errors throws {@link ModelException} carrying all of them.
 *
 * <p>Each load runs on a thread with a large stack ({@link LargeStack}), so that models nested up to the front
 * end's limit (expressions, statements, initialiser braces and types 1,000 levels deep, each) load whatever
 * thread asks; a model that still exhausts that stack is a {@link ModelException}. A model too large for the
 * heap ends the load with the {@link OutOfMemoryError}, thrown in the caller's thread after the loading thread
 * has ended, so that what it had built is garbage by then.
 */
public final class ModelLoader {
    private ModelLoader() {
    }

    /** Loads a model file. */
    public static Network load(Path file) throws ModelException {
        String name = file.toString();
        return onLargeStack(name, () -> compile(ModelSyntax.parseModel(name, read(file, name))));
    }

    private static String read(Path file, String name) throws ModelException {
        try {
            return ModelSyntax.decode(Files.readAllBytes(file));
        } catch (NoSuchFileException e) {
            throw new ModelException(List.of(Diagnostic.fileError(name, "no such file")));
        } catch (IOException e) {
            throw new ModelException(List.of(Diagnostic.fileError(name, "cannot read the file: " + e.getMessage())));
        }
    }

    /** Loads a model from its text; {@code name} is used in messages. XML is recognised by its first {@code <}. */
    public static Network load(String name, String text) throws ModelException {
        return onLargeStack(name, () -> compile(ModelSyntax.parseModel(name, text)));
    }

    private static Network compile(Parsed<Nta> parsed) throws ModelException {
        if (parsed.hasErrors()) {
            throw new ModelException(parsed.diagnostics());
        }
        Parsed<Network> compiled = NetworkCompiler.compile(parsed.value());
        if (compiled.hasErrors()) {
            List<Diagnostic> all = new ArrayList<>(parsed.diagnostics());
            all.addAll(compiled.diagnostics());
            throw new ModelException(all);
        }
        Network network = compiled.value();
        if (parsed.diagnostics().isEmpty()) {
            return network;
        }
        List<Diagnostic> warnings = new ArrayList<>(parsed.diagnostics());
        warnings.addAll(network.warnings());
        warnings.sort(Diagnostic.BY_POSITION);
        return new Network(network.file(), network.processes(), network.variables(), network.clocks(),
                network.channels(), network.functions(), network.stateSize(), network.clockCount(),
                network.channelCount(), network.channelPriority(), network.queries(), warnings, network.startErrors());
    }

    /**
     * Runs {@code load} on a thread with a large stack; a stack overflow there is a model error of file
     * {@code name}.
     */
    private static Network onLargeStack(String name, LargeStack.Work<Network, ModelException> load)
            throws ModelException {
        try {
            return LargeStack.call(load);
        } catch (StackOverflowError e) {
            throw new ModelException(List.of(Diagnostic.fileError(name, "the model is nested too deeply to load: it"
                    + " overflowed the loader's stack of " + LargeStack.MEGABYTES + " MB")));
        }
    }

    /** Loads a model from the classpath of {@code loader}. */
    public static Network loadResource(ClassLoader loader, String resource) throws ModelException {
        try (InputStream in = loader.getResourceAsStream(resource)) {
            if (in == null) {
                throw new ModelException(List.of(Diagnostic.fileError(resource, "no such resource on the classpath")));
            }
            return load(resource, ModelSyntax.decode(in.readAllBytes()));
        } catch (IOException e) {
            throw new ModelException(List.of(Diagnostic.fileError(resource, "cannot read: " + e.getMessage())));
        }
    }

    /** Loads the model stored under {@code name}. */
    public static Network load(ModelStore store, String name) throws ModelException {
        String text = store.get(name).orElseThrow(() -> new ModelException(
                List.of(Diagnostic.fileError(name, "no model of that name in the store"))));
        return load(name, text);
    }
}
