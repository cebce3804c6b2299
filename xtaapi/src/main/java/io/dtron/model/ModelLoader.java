package io.dtron.model;

import io.dtron.model.internal.NetworkCompiler;
import io.dtron.xta.Diagnostic;
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
 */
public final class ModelLoader {
    private ModelLoader() {
    }

    /** Loads a model file. */
    public static Network load(Path file) throws ModelException {
        String name = file.toString();
        byte[] bytes;
        try {
            bytes = Files.readAllBytes(file);
        } catch (NoSuchFileException e) {
            throw new ModelException(List.of(Diagnostic.fileError(name, "no such file")));
        } catch (IOException e) {
            throw new ModelException(List.of(Diagnostic.fileError(name, "cannot read the file: " + e.getMessage())));
        }
        return load(name, ModelSyntax.decode(bytes));
    }

    /** Loads a model from its text; {@code name} is used in messages. XML is recognised by its first {@code <}. */
    public static Network load(String name, String text) throws ModelException {
        Parsed<Nta> parsed = ModelSyntax.parseModel(name, text);
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
        return new Network(network.file(), network.processes(), network.variables(), network.clocks(),
                network.channels(), network.functions(), network.stateSize(), network.clockCount(),
                network.channelCount(), network.channelPriority(), network.queries(), warnings, network.startErrors());
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
