package io.dtron.xta;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Nta;
import java.nio.file.Path;
import java.util.List;
import java.util.stream.Collectors;
import java.util.stream.Stream;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

class SharedModelsParseTest {

    static Stream<Path> models() {
        return SharedModels.modelFiles().stream();
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("models")
    void everySharedModelParsesWithoutSyntaxErrors(Path file) {
        Parsed<Nta> parsed = ModelSyntax.parseModel(file.getFileName().toString(), SharedModels.read(file));
        String errors = parsed.diagnostics().stream().map(Diagnostic::format).collect(Collectors.joining("\n"));
        if (file.getFileName().toString().equals("err-13.xta")) {
            // an empty IO list, "IO P1{}", is a syntax error in Uppaal too
            assertEquals(List.of("err-13.xta:25:7: error: syntax error: unexpected '}'"),
                    parsed.diagnostics().stream().map(Diagnostic::format).toList());
            return;
        }
        assertFalse(parsed.hasErrors(), errors);
        assertNotNull(parsed.value());
        assertNotNull(parsed.value().system(), "every shared model has a system line");
        assertFalse(parsed.value().templates().isEmpty(), "every shared model has a template");
    }

    @Test
    void thereAreSharedModelsToParse() {
        assertTrue(SharedModels.modelFiles().size() >= 80, "found " + SharedModels.modelFiles().size());
    }

    @Test
    void trainGateHasItsTemplatesLocationsAndQueries() {
        Path file = SharedModels.root().resolve("uppaal-examples/train-gate-utap.xml");
        Nta nta = ModelSyntax.parseModel("train-gate-utap.xml", SharedModels.read(file)).value();
        List<String> names = nta.templates().stream().map(Decl.Template::name).toList();
        assertEquals(List.of("Train", "Gate"), names);
        Decl.Template train = nta.templates().get(0);
        assertEquals(5, train.locations().size());
        assertEquals(6, train.edges().size());
        assertEquals("id0", train.init());
        assertTrue(nta.queries().size() >= 5, "queries: " + nta.queries().size());
    }
}
