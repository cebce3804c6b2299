package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.internal.parser.UppaalLexer;
import io.dtron.xta.internal.parser.UppaalParser;
import java.util.List;
import java.util.function.Function;
import org.antlr.v4.runtime.BailErrorStrategy;
import org.antlr.v4.runtime.CharStreams;
import org.antlr.v4.runtime.CommonTokenStream;
import org.antlr.v4.runtime.DefaultErrorStrategy;
import org.antlr.v4.runtime.ParserRuleContext;
import org.antlr.v4.runtime.atn.PredictionMode;
import org.antlr.v4.runtime.misc.ParseCancellationException;

/**
 * Runs the generated parser on one fragment: first in the fast SLL mode that bails out at the first
 * problem, then, only if that fails, in full LL mode with error recovery so that all syntax errors of the
 * fragment are reported.
 */
final class ParserDriver {
    private ParserDriver() {
    }

    /** The parse tree of the fragment by the given entry rule, or null with errors added to {@code out}. */
    static <T extends ParserRuleContext> T parse(Fragment fragment, Function<UppaalParser, T> rule,
                                                  List<Diagnostic> out) {
        UppaalLexer lexer = new UppaalLexer(CharStreams.fromString(fragment.text(), fragment.file()));
        lexer.removeErrorListeners();
        CommonTokenStream tokens = new CommonTokenStream(lexer);
        UppaalParser parser = new UppaalParser(tokens);
        parser.removeErrorListeners();
        parser.getInterpreter().setPredictionMode(PredictionMode.SLL);
        parser.setErrorHandler(new BailErrorStrategy());
        try {
            return rule.apply(parser);
        } catch (ParseCancellationException bail) {
            tokens.seek(0);
            parser.reset();
            parser.getInterpreter().setPredictionMode(PredictionMode.LL);
            parser.setErrorHandler(new DefaultErrorStrategy());
            SyntaxErrorCollector collector = new SyntaxErrorCollector(fragment);
            parser.addErrorListener(collector);
            T tree = rule.apply(parser);
            if (collector.diagnostics().isEmpty()) {
                return tree;
            }
            out.addAll(collector.diagnostics());
            return null;
        }
    }
}
